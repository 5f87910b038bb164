#pragma once

// What a network's per-vertex values mean (the paper's Table 2): offsets in the embedded local frames, offsets in the
// root frame, or positions in the root frame. The body's root (pelvis) is never rotated or moved, so the root frame is
// the world frame of the dataset.

#include <Eigen/Core>
#include <string>

#include "pixelcloth/garment/embedding.h"

namespace pixelcloth::learn {

enum class OffsetSpace {
  Local,      ///< (du, dv, dn) in each cloth pixel's embedded frame: the paper's choice for the T-shirt
  Root,       ///< (dx, dy, dz) = position - embedded point: the necktie's
  Positions,  ///< (x, y, z): positions in the root frame
};

/// "local", "root", "positions".
const char* offsetSpaceName(OffsetSpace space);
OffsetSpace offsetSpaceFromName(const std::string& name, const std::string& context);

/// The values (#V x 3) of garment positions (#V x 3, metres) in `space`, on the posed body whose frames are `frames`.
Eigen::MatrixX3f valuesInSpace(OffsetSpace space, const garment::EmbeddedFrames& frames,
                               const Eigen::MatrixX3d& positions);
/// Back: the positions of values in `space`. Exact inverse of valuesInSpace (orthonormal frames).
Eigen::MatrixX3d positionsFromValues(OffsetSpace space, const garment::EmbeddedFrames& frames,
                                     const Eigen::MatrixX3f& values);

}  // namespace pixelcloth::learn
