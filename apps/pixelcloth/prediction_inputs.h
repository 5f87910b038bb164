#pragma once

// What predict and evaluate feed a trained model: the model, and the rows it predicts (inputs, frames, base).

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
                                         const std::filesystem::path& base);

/// One row: the pose in `posePath` on the body of `dataset` (default: the model's training dataset); a residual
/// model's base rebuilt from the markers in `markersPath` as its base folder's settings say.
PredictionInputs posePredictionInputs(const std::filesystem::path& modelFolder, const std::filesystem::path& posePath,
                                      const std::filesystem::path& markersPath, const std::filesystem::path& dataset);

}  // namespace pixelcloth::apps
