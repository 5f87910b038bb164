#pragma once

// What a trained model predicts from (DESIGN.md, "Networks"): the model, checked against the dataset whose body and
// garment it was trained on, and the rows it predicts: inputs (the pose, plus marker features in residual mode), the
// posed body's frames, and in residual mode the base the residual is added to (the paper's Sec. 5.2).

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/training_data.h"

namespace pixelcloth::learn {

struct PredictionInputs {
  std::unique_ptr<TrainedModel> model;
  TrainingData data;
};

/// Every row of `dataset`, for the model in `modelFolder` (checked against the dataset); a residual model's base
/// folder is `base`, by default the one it was trained with. Throws InputError for a model of another garment or
/// body, or a `base` given to a model that takes the pose alone.
PredictionInputs datasetPredictionInputs(const std::filesystem::path& modelFolder, const data::DatasetFolder& dataset,
                                         const std::filesystem::path& base, Engine engine);

/// One row: `pose` (read from `poseName`, for messages) on the body of `dataset` (empty: the model's training
/// dataset). A residual model's row is finished by addPoseBase. Throws InputError when the pose turns joints beyond
/// the model's pose size.
PredictionInputs posePredictionInputs(const std::filesystem::path& modelFolder, const body::Pose& pose,
                                      const std::string& poseName, const data::DatasetFolder& dataset, Engine engine);

/// One row per pose (a motion's frames, in order), as posePredictionInputs makes one; `name` names the poses' source
/// in messages. Progress on stderr.
PredictionInputs posesPredictionInputs(const std::filesystem::path& modelFolder, const std::vector<body::Pose>& poses,
                                       const std::string& name, const data::DatasetFolder& dataset, Engine engine);
/// The same with the model already loaded (checked against `dataset`, which must be given).
PredictionInputs posesPredictionInputs(std::unique_ptr<TrainedModel> model, const std::vector<body::Pose>& poses,
                                       const std::string& name, const data::DatasetFolder& dataset);

/// Completes the one row of a residual model's posePredictionInputs: the base offsets (#V x 3, du dv dn in the posed
/// body's frames) rebuilt from the garment's markers and their 3M marker features (recon::baseOfCapture).
void addPoseBase(PredictionInputs& inputs, const Eigen::MatrixX3d& baseOffsets, const Eigen::VectorXd& features);
/// The same for every row of a residual model's posesPredictionInputs (a capture's frames): one base per row and
/// one row of 3M marker features per row.
void addPoseBases(PredictionInputs& inputs, const std::vector<Eigen::MatrixX3d>& baseOffsets,
                  const Eigen::MatrixXd& features);

}  // namespace pixelcloth::learn
