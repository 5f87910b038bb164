#pragma once

// What predict and evaluate feed a trained model: the model, and the rows it predicts (inputs, frames, base).

#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <string>

#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/training_data.h"

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

}  // namespace pixelcloth::apps
