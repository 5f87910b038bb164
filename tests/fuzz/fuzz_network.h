#pragma once

// The small network the weights and checkpoint targets load into: a fully connected baseline, 4 inputs to 6 values at
// width 0.05. Its own saveWeights / saveCheckpoint output is the seed corpus (PIXELCLOTH_FUZZ_SEED_OUT, README.md).

#include <cstdlib>
#include <filesystem>

#include "checkpoint.h"
#include "fuzz_support.h"
#include "model_impl.h"
#include "pixelcloth/core/tensor_file.h"

namespace pixelcloth::fuzz {

inline learn::ModelSpec fuzzSpec() {
  learn::ModelSpec spec;
  spec.architecture = learn::Architecture::FullyConnected;
  spec.width = 0.05;
  spec.inputSize = 4;
  spec.outputValues = 6;
  return spec;
}

/// Beside the seed `file` (a tensor file of `kind`), the same file whose header's meta holds a value nested 1000 deep:
/// the hostile input that once overflowed the stack when the header was copied (docs/reliability.md, finding 15).
inline void writeDeepMetaSeed(const std::filesystem::path& file, const std::string& kind) {
  core::TensorFile tensors = core::readTensorFile(file, kind);
  tensors.meta["nested"] = nlohmann::json::parse(deepNesting(1000));
  core::writeTensorFile(file.parent_path() / ("deep_meta_" + file.filename().string()), tensors);
}

}  // namespace pixelcloth::fuzz
