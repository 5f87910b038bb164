#pragma once

// A dataset as the trainer and the evaluation see it (learn/-internal): every row's network input (pose, plus the
// marker features in residual mode) and its per-vertex target values in the model's space (ground truth minus the
// base in residual mode), with the posed frames the geometric losses and positions need.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/learn/spaces.h"

namespace pixelcloth::learn {

struct TrainingData {
  std::filesystem::path folder;
  data::DatasetInfo info;
  std::uint32_t manifestCrc = 0;  ///< CRC-32 of the dataset's manifest.json
  garment::Garment garment;
  OffsetSpace space = OffsetSpace::Local;
  std::filesystem::path baseFolder;  ///< residual mode's base folder; empty in plain mode
  std::uint32_t baseCrc = 0;         ///< CRC-32 of its manifest.json
  int poseSize = 0, markers = 0;
  Eigen::MatrixXf inputs;                ///< rows x (poseSize + 3 markers)
  std::vector<Eigen::MatrixXf> values;   ///< per row: #V x 3, the target in `space`
  std::vector<Eigen::MatrixXf> base;     ///< per row: #V x 3, the base in `space` (residual mode; else empty)
  std::vector<Eigen::MatrixXf> truth;    ///< per row: #V x 3 ground-truth positions
  std::vector<garment::EmbeddedFrames> frames;  ///< per row: the posed body's frames of the cloth pixels
  std::vector<int> train, regularisation, test;

  int rows() const { return static_cast<int>(values.size()); }
  bool residual() const { return !baseFolder.empty(); }
  /// The rows of a split.
  const std::vector<int>& split(data::Split which) const;
};

/// Reads a finished dataset (and, when `baseFolder` is not empty, its base folder, checked against it) into the
/// trainer's form.
TrainingData loadTrainingData(const data::DatasetFolder& dataset, OffsetSpace space,
                              const std::filesystem::path& baseFolder);

}  // namespace pixelcloth::learn
