#pragma once

// A LibTorch module's parameters and buffers in a pixelcloth tensor file (core/tensor_file.h), not a LibTorch archive:
// LibTorch 1.13's archive reader crashes on damaged files (docs/reliability.md, finding 12). Used for every network's
// model.tensors, the GAN blender's included.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "pixelcloth/core/tensor_file.h"

namespace torch::nn {
class Module;
}

namespace pixelcloth::learn {

/// The module's parameters then buffers, named as LibTorch names them ("0.weight", "down.1.running_mean"), each
/// prefixed with `prefix`, appended to `file`.
void appendModuleArrays(const torch::nn::Module& module, core::TensorFile& file, const std::string& prefix = "");

/// Copies the arrays named `prefix` + each parameter's and buffer's name into the module. Throws `InputError` naming
/// `file` for a missing array, one of another dtype or shape, one that is not finite, and (when `prefix` is empty)
/// an array the module has not: all say the file holds the weights of another network than `what`.
void loadModuleArrays(torch::nn::Module& module, const core::TensorFile& file, const std::filesystem::path& path,
                      const std::string& what, const std::string& prefix = "");

/// Writes the module's weights (kind "weights") atomically, with `meta` in the header.
void saveModuleWeights(const torch::nn::Module& module, const std::filesystem::path& path,
                       const nlohmann::json& meta = nlohmann::json::object());

/// Reads weights written by saveModuleWeights into the module: InputError naming the file, as readTensorFile and
/// loadModuleArrays say.
void loadModuleWeights(torch::nn::Module& module, const std::filesystem::path& path, const std::string& what);

}  // namespace pixelcloth::learn
