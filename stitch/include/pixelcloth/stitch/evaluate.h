#pragma once

// Garments predicted for dataset samples by a trained model, and their errors and seam continuity against ground
// truth (DESIGN.md, "Metrics").

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/training_data.h"
#include "pixelcloth/stitch/stitcher.h"

namespace pixelcloth::stitch {

/// Predicted garments of some dataset rows.
struct RowPredictions {
  std::vector<int> rows;
  std::vector<Eigen::MatrixX3f> values;     ///< per row: #V x 3 in the model's space, the base added
  std::vector<Eigen::MatrixX3d> positions;  ///< per row: #V x 3, metres
  /// Per row, when predictRows measured it: meanSeamGapCm of the networks' own predictions before blending (NaN for
  /// a whole-garment model); empty otherwise.
  std::vector<double> seamGapCm;
};

/// Predicts `rows` of `data` (loaded in the model's space, with its base folder in residual mode): the networks'
/// outputs assembled by `stitcher` (nullptr: the per-vertex mean), the base added, then the stitcher's filter or
/// blender, positions through the row's posed frames. Throws InputError naming the missing patches of an incomplete
/// patch model. With `measureSeamGaps`, also each row's seam gap (RowPredictions::seamGapCm).
RowPredictions predictRows(const learn::TrainedModel& model, const learn::TrainingData& data,
                           const std::vector<int>& rows, const Stitcher* stitcher = nullptr,
                           bool measureSeamGaps = false);

/// Each network's own positions of the vertices it covers, before blending, for batch row `k` of `predictions`: its
/// values (plus `base`, #V x 3 in `space`, when not null) through the posed `frames`. One matrix per prediction, its
/// vertices' order: what SeamMetrics measures the gaps on.
std::vector<Eigen::MatrixX3d> separatePositions(const std::vector<learn::NetworkPrediction>& predictions,
                                                learn::OffsetSpace space, const garment::EmbeddedFrames& frames,
                                                const Eigen::MatrixXf* base, Eigen::Index k);

/// What evaluate() measured for one stitch mode.
struct Evaluation {
  StitchMode mode;  ///< how the predictions were stitched (the plain mean when evaluate() was given no stitcher)
  /// {"split", "samples", "stitch" (the mode's name), "vertex_error_cm", "max_vertex_error_cm", "normal_cosine" (mean
  /// cosine between predicted and true per-vertex normals), "normal_cosine_distance" (1 - that),
  /// "base_vertex_error_cm" (residual mode: the marker reconstruction alone; null otherwise), "patches": [{"id",
  /// "layout", "vertices", "vertex_error_cm"}], "seams": SeamMetrics::toJson()}.
  nlohmann::json metrics;
  Eigen::VectorXd vertexErrorCm;  ///< #V: each vertex's mean error over the split, cm
  std::vector<int> rows;          ///< the split's rows of the data, in order
  std::vector<Eigen::MatrixX3f> positions;  ///< per row: the stitched prediction, #V x 3, as data.truth
  /// The `q`-quantile (0 to 1) of vertexErrorCm, cm: e.g. the top of an error map's colour scale.
  double vertexErrorQuantileCm(double q) const;
};

/// Predicts every row of `split` once and compares each of `stitchers` (empty: the plain mean) with ground truth; one
/// Evaluation per stitcher, in order. Throws InputError for an empty split.
std::vector<Evaluation> evaluate(const learn::TrainedModel& model, const learn::TrainingData& data, data::Split split,
                                 const std::vector<const Stitcher*>& stitchers = {});

/// The garments of `evaluation` for pixelcloth view: predictions.npy in `folder` (rows x #V x 3, float32, as the
/// dataset's positions.npy), and in `metrics` "rows", the dataset sample of each.
void writePredictions(const std::filesystem::path& folder, const Evaluation& evaluation,
                      const learn::TrainingData& data, nlohmann::json& metrics);

/// The pca:K evaluation with the lowest mean vertex error: the k chosen on the split `evaluations` measured (the
/// regularisation split, to report the test split at that k). -1 when none is a pca:K mode.
int bestPcaMode(const std::vector<Evaluation>& evaluations);

}  // namespace pixelcloth::stitch
