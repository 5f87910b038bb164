#pragma once

// Garments predicted for dataset samples by a trained model, and their errors against ground truth (DESIGN.md,
// "Metrics"; the seam-continuity metrics come with issue 14).

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/training_data.h"

namespace pixelcloth::stitch {

/// Predicted garments of some dataset rows.
struct RowPredictions {
  std::vector<int> rows;
  std::vector<Eigen::MatrixX3f> values;     ///< per row: #V x 3 in the model's space, the base added back
  std::vector<Eigen::MatrixX3d> positions;  ///< per row: #V x 3, metres
};

/// Predicts `rows` of `data` (loaded in the model's space, with its base folder in residual mode): the networks'
/// outputs assembled by the per-vertex mean, the base added, positions through the row's posed frames.
RowPredictions predictRows(const learn::TrainedModel& model, const learn::TrainingData& data,
                           const std::vector<int>& rows);

/// What evaluate() measured.
struct Evaluation {
  /// {"split", "samples", "vertex_error_cm", "max_vertex_error_cm", "normal_cosine" (mean cosine between predicted
  /// and true per-vertex normals), "normal_cosine_distance" (1 - that), "base_vertex_error_cm" (residual mode: the
  /// marker reconstruction alone; null otherwise), "patches": [{"id", "layout", "vertices", "vertex_error_cm"}]}.
  nlohmann::json metrics;
  Eigen::VectorXd vertexErrorCm;  ///< #V: each vertex's mean error over the split, cm
  /// The `q`-quantile (0 to 1) of vertexErrorCm, cm: e.g. the top of an error map's colour scale.
  double vertexErrorQuantileCm(double q) const;
};

/// Predicts every row of `split` and compares with ground truth. Throws InputError for an empty split.
Evaluation evaluate(const learn::TrainedModel& model, const learn::TrainingData& data, const std::string& split);

}  // namespace pixelcloth::stitch
