#pragma once

// A motion through a trained model (the paper's Sec. 6 evaluation on motion capture): every frame predicted in
// batches, the garment and body written as an animated GLB, an OBJ sequence and PC2 caches, with the temporal
// measures. `predict --motion` and the demo both call it.

#include <filesystem>
#include <string>
#include <vector>

#include "pixelcloth/learn/prediction_inputs.h"
#include "pixelcloth/motion/motion.h"
#include "pixelcloth/motion/sequence.h"
#include "pixelcloth/stitch/stitcher.h"

namespace pixelcloth::eval {

/// What predictMotion wrote and measured.
struct MotionPrediction {
  int frames = 0;
  double fps = 0;
  double predictSeconds = 0;  ///< the networks and the stitching, all frames
  motion::TemporalMetrics metrics;
  std::vector<Eigen::MatrixX3d> garment, body;  ///< per frame, in the body's root frame
  std::vector<std::string> files;               ///< written into the output folder, relative to it
};

/// Predicts every frame of `clip` with `inputs` (learn::posesPredictionInputs of its poses; not a residual model) and
/// `stitcher`, and writes into `out`: animation.glb, frames/garment_NNNN.obj, garment.obj and body.obj (frame 0),
/// garment.pc2 and body.pc2 (the clip's root motion applied), metrics.json (the temporal measures, `info` added).
MotionPrediction predictMotion(const learn::PredictionInputs& inputs, const stitch::Stitcher& stitcher,
                               const motion::Motion& clip, const std::filesystem::path& out,
                               const nlohmann::json& info = nlohmann::json::object());

}  // namespace pixelcloth::eval
