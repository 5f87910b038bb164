#pragma once

// Model folders on disk (learn/-internal): the JSON sidecar, the weights (model.tensors), and the training checkpoint that
// a run resumes from.

#include <torch/torch.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "pixelcloth/learn/model.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/learn/training_data.h"

namespace pixelcloth::learn {

/// "patch_07".
std::string patchFolderName(int patch);

/// model.json before its epoch and errors: {"format": "pixelcloth.model", "version", "architecture", "width",
/// "inputs", "output", "values", "pca_components", "garment", "vertices", "pose_size", "markers", "space", "loss",
/// "dataset", "dataset_manifest_crc32", "residual": {"folder", "manifest_crc32"} | null, "patch": id | null}.
nlohmann::json modelSidecar(const ModelSpec& spec, const TrainingData& data, int patch, const std::string& loss);

/// The spec a sidecar describes, checked (InputError naming `context`).
ModelSpec specOfSidecar(const nlohmann::json& sidecar, const std::string& context);

/// Writes the network's weights and buffers as a pixelcloth tensor file (core/tensor_file.h), atomically.
void saveWeights(const torch::nn::Sequential& net, const std::filesystem::path& path);
/// Loads weights into `net`, checking every tensor's shape (LibTorch's own load takes any): InputError naming the
/// file for a missing, truncated, damaged or foreign file.
void loadWeights(torch::nn::Sequential& net, const std::filesystem::path& path, const std::string& what);

/// checkpoint.tensors: the weights, the optimizer's state, the epochs so far and the run's signature, in one tensor
/// file written atomically.
void saveCheckpoint(const std::filesystem::path& path, const nlohmann::json& signature,
                    const torch::nn::Sequential& net, torch::optim::Adam& adam, const NetworkReport& report);
/// Restores them; InputError when the file is damaged or its signature differs (naming the first setting that does).
void loadCheckpoint(const std::filesystem::path& path, const nlohmann::json& signature, torch::nn::Sequential& net,
                    torch::optim::Adam& adam, NetworkReport& report);

}  // namespace pixelcloth::learn
