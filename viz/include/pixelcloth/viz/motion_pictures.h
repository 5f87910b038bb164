#pragma once

// Pictures of a predicted sequence: the garment on the moving body, a few frames side by side, and its temporal
// measures against the frame.

#include <Eigen/Core>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "pixelcloth/core/image.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/eval/motion_prediction.h"
#include "pixelcloth/motion/sequence.h"
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

/// The view of the frame strips: 240 x 320, from 20 degrees to the side and 10 above; bounds left to the caller.
View frameStripView();

/// `count` of `frames` frames spread evenly from the first to the last, each drawn by `render(frame)` and labelled
/// with its number and its time at `fps`, side by side.
core::RgbImage renderFrameStrip(int frames, int count, double fps, const std::function<core::RgbImage(int)>& render);

/// `count` frames spread evenly from the first to the last, side by side on one scale: the body (`bodyFaces` with
/// each frame's positions) and the garment (`garment`'s faces and panels) over it, each labelled with its frame and
/// time at `fps`.
core::RgbImage renderGarmentStrip(const Eigen::MatrixX3i& bodyFaces, const std::vector<Eigen::MatrixX3d>& body,
                                  const core::Mesh& garment, const std::vector<Eigen::MatrixX3d>& garmentFrames,
                                  double fps, int count = 8);

/// Charts against time: the garment's and the body's jitter, the garment vertices inside the body, and the seam gap
/// when it was measured.
core::RgbImage renderTemporalMetrics(const motion::TemporalMetrics& metrics);

/// Writes `sequence`'s pictures into `out`: strip.png (renderGarmentStrip of the body, faces `bodyFaces`, and the
/// garment, faces of `garment`) and temporal.png (renderTemporalMetrics). Returns their names.
std::vector<std::string> writeSequencePictures(const std::filesystem::path& out, const Eigen::MatrixX3i& bodyFaces,
                                               const core::Mesh& garment, const eval::MotionPrediction& sequence);

}  // namespace pixelcloth::viz
