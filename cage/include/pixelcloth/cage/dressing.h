#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "pixelcloth/cage/cage.h"
#include "pixelcloth/core/body.h"
#include "pixelcloth/core/embedding.h"
#include "pixelcloth/core/garment.h"
#include "pixelcloth/core/image.h"

namespace pixelcloth::cage {

/// Settings of dressing (DESIGN.md "Dressing"; paper appendix, "dressing").
struct DressingOptions {
  double clearance = 0.003;       ///< cloth sits this far outside the body surface (metres)
  int maxRelaxIterations = 400;   ///< edge-length equalisation sweeps at most
  double relaxTolerance = 2e-5;   ///< stop when no vertex moves more than this in a sweep (metres)
  void validate() const;
};

/// A garment dressed on a body in its rest pose.
struct Dressing {
  Eigen::MatrixX3d morphed;   ///< #V x 3: cage morphed onto the body cage, carried inside by a Poisson solve
  Eigen::MatrixX3d pushed;    ///< #V x 3: `morphed` with vertices inside the body moved out to the surface
  Eigen::MatrixX3d relaxed;   ///< #V x 3: after edge-length equalisation on the body: the dressed garment
  core::Embedding embedding;  ///< every cloth vertex of `relaxed`, embedded in a body triangle
  std::vector<int> part;      ///< #V: index into Body::parts of the part each cloth vertex collides with
  Eigen::VectorXd areaRatioBefore;  ///< #F: 3D area of `pushed` over pattern area
  Eigen::VectorXd areaRatioAfter;   ///< #F: 3D area of `relaxed` over pattern area
  int relaxIterations = 0;
  double relaxResidual = 0;  ///< largest vertex move of the last sweep (metres)
};

/// Dresses `garment` on `body` (rest T-pose). Cage curves of `garmentCage` that have a namesake in `bodyCage` are
/// morphed onto it by arc length between the junctions they share; curves without one (the shirt's side-panel lines)
/// and all interior vertices follow through a Poisson solve on the garment mesh; then push-out, relaxation and
/// embedding. A garment none of whose curves have a body counterpart (the necktie) keeps its rest placement, pushed
/// out of the body. Throws InputError when the cages do not fit the meshes or the result is not finite.
Dressing dressGarment(const core::Body& body, const Cage& bodyCage, const core::Garment& garment,
                      const Cage& garmentCage, const DressingOptions& options = {});

/// Area distortion in pattern space, before and after relaxation side by side: faces coloured by
/// log2(3D area / pattern area), red for stretch, blue for compression, white for none; with a colour bar.
core::RgbImage renderAreaDistortion(const core::Garment& garment, const Dressing& dressing, int pixelsPerMetre = 800);

}  // namespace pixelcloth::cage
