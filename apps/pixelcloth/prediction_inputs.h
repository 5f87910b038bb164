#pragma once

// The options predict and evaluate share: the engine, the stitch modes, and a pose file's prediction inputs.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <string>

#include "pixelcloth/eval/motion_prediction.h"
#include "pixelcloth/learn/prediction_inputs.h"
#include "pixelcloth/stitch/stitcher.h"

namespace pixelcloth::apps {

/// learn::posePredictionInputs of the pose file `posePath`, finished for a residual model with the base rebuilt from
/// the markers in `markersPath` as its base folder's settings say (recon::baseOfCapture).
learn::PredictionInputs posePredictionInputs(const std::filesystem::path& modelFolder,
                                             const std::filesystem::path& posePath,
                                             const std::filesystem::path& markersPath,
                                             const data::DatasetFolder& dataset, learn::Engine engine);

/// Adds `--engine onednn|libtorch` (which runs the networks) to a verb.
void addEngineOption(CLI::App& verb, std::string& engine);

/// What --stitch and --pca said.
struct StitchArgs {
  std::string modes = "mean";
  std::string pca;   ///< a PCA filter folder; empty: the model folder's pca/ (fitted there on first use)
  int pcaRank = 0;   ///< rank when a filter is fitted here; 0: min(2048, train samples, 3 #V)
};

/// Adds `--stitch` (one mode, or several separated by commas when `several`), `--pca` and `--pca-rank` to a verb.
void addStitchOptions(CLI::App& verb, StitchArgs& args, bool several);

/// The stitchers of `args.modes` for `inputs`. A pca mode loads the filter in `args.pca` and checks that it was
/// fitted on this dataset; without --pca it uses the model folder's pca/, fitting it on the dataset's train split
/// (and saving it there) when it is missing or was fitted on another dataset.
std::vector<stitch::Stitcher> makeStitchers(const StitchArgs& args, const learn::PredictionInputs& inputs);

/// One line on a written garment sequence (predict --motion, reconstruct --markers-sequence): "73 frames at 24 fps in
/// 1.2 s (16.4 ms a frame); garment jitter ...; seam gap ...; garment inside the body in 3 frames -> OUT/{files}".
std::string sequenceSummary(const eval::MotionPrediction& sequence, const std::filesystem::path& out);

}  // namespace pixelcloth::apps
