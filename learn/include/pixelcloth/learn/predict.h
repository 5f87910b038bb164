#pragma once

// A trained model folder, loaded for prediction: one network (model.json at its top) or patch decoders (patch_NN/
// folders, possibly trained by separate runs).

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/learn/inference.h"
#include "pixelcloth/learn/model.h"
#include "pixelcloth/learn/spaces.h"

namespace pixelcloth::learn {

/// What one network predicted for a batch.
struct NetworkPrediction {
  int patch = -1;             ///< patch id of a patch decoder, -1 otherwise
  std::vector<int> vertices;  ///< garment vertices it covers, ascending
  Eigen::MatrixXf values;     ///< batch x 3 * vertices.size(): each covered vertex's 3 values, in the model's space
};

class TrainedModel {
 public:
  /// Loads `folder` for `garment` (the garment of the dataset it was trained on, e.g. data::datasetGarment). Throws
  /// InputError naming the file for a missing, truncated or foreign checkpoint, a model of another garment, or patch
  /// folders that disagree (architecture, width, dataset, base). `engine` runs predict(): oneDNN (the networks
  /// compiled once here, all of them in one call on `threads` cores, 0: every core) or LibTorch's modules.
  TrainedModel(const std::filesystem::path& folder, const garment::Garment& garment, Engine engine = Engine::OneDnn,
               int threads = 0);
  ~TrainedModel();
  TrainedModel(TrainedModel&&) noexcept;

  const std::filesystem::path& folder() const;
  /// The first network's model.json (every network of a patch folder shares all but patch, epoch and errors).
  const nlohmann::json& sidecar() const;
  Architecture architecture() const;
  OffsetSpace space() const;
  int inputs() const;         ///< pose size + 3 markers
  int poseSize() const;
  int markers() const;        ///< marker features' markers (0 in plain mode)
  bool residual() const;
  std::filesystem::path baseFolder() const;  ///< the base folder it was trained with (residual mode)
  /// Patch ids present (patch models), ascending; empty otherwise.
  std::vector<int> patches() const;
  /// Throws InputError unless `dataset` has this model's garment (vertex count) and pose size.
  void checkDataset(const data::DatasetInfo& dataset) const;

  Engine engine() const;
  /// Every network's prediction for `inputs` (batch x inputs(): frames in one call share each weight's trip from
  /// memory), BatchNorm in eval mode. The oneDNN engine keeps per-batch-size state: not for concurrent calls.
  std::vector<NetworkPrediction> predict(const Eigen::MatrixXf& inputs) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The dataset folder a model folder was trained on (its model.json, or its first patch's), as recorded.
std::filesystem::path trainingDatasetOf(const std::filesystem::path& modelFolder);

}  // namespace pixelcloth::learn
