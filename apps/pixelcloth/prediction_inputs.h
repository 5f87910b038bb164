#pragma once

// What predict and evaluate feed a trained model: the model, and the rows it predicts (inputs, frames, base).

#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <string>

#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/training_data.h"
#include "pixelcloth/stitch/stitcher.h"

namespace pixelcloth::apps {

struct PredictionInputs {
  std::unique_ptr<learn::TrainedModel> model;
  learn::TrainingData data;
};

/// Every row of a dataset, for the model in `modelFolder` (checked against the dataset); a residual model's base
/// folder is `base`, by default the one it was trained with.
PredictionInputs datasetPredictionInputs(const std::filesystem::path& modelFolder, const std::filesystem::path& dataset,
                                         const std::filesystem::path& base, learn::Engine engine);

/// One row: the pose in `posePath` on the body of `dataset` (default: the model's training dataset); a residual
/// model's base rebuilt from the markers in `markersPath` as its base folder's settings say.
PredictionInputs posePredictionInputs(const std::filesystem::path& modelFolder, const std::filesystem::path& posePath,
                                      const std::filesystem::path& markersPath, const std::filesystem::path& dataset,
                                      learn::Engine engine);

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
std::vector<stitch::Stitcher> makeStitchers(const StitchArgs& args, const PredictionInputs& inputs);

}  // namespace pixelcloth::apps
