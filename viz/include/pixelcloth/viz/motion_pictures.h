#pragma once

// Pictures of a predicted sequence: the garment on the moving body, a few frames side by side, and its temporal
// measures against the frame.

#include <Eigen/Core>
#include <vector>

#include "pixelcloth/core/image.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/motion/sequence.h"

namespace pixelcloth::viz {

/// `count` frames spread evenly from the first to the last, side by side on one scale: the body (`bodyFaces` with
/// each frame's positions) and the garment (`garment`'s faces and panels) over it, each labelled with its frame and
/// time at `fps`.
core::RgbImage renderGarmentStrip(const Eigen::MatrixX3i& bodyFaces, const std::vector<Eigen::MatrixX3d>& body,
                                  const core::Mesh& garment, const std::vector<Eigen::MatrixX3d>& garmentFrames,
                                  double fps, int count = 8);

/// Two charts against time: the garment's and the body's jitter, and the garment vertices inside the body.
core::RgbImage renderTemporalMetrics(const motion::TemporalMetrics& metrics);

}  // namespace pixelcloth::viz
