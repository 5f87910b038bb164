#pragma once

// The small network the weights and checkpoint targets load into: a fully connected baseline, 4 inputs to 6 values at
// width 0.05. Its own saveWeights / saveCheckpoint output is the seed corpus (PIXELCLOTH_FUZZ_SEED_OUT, README.md).

#include <cstdlib>
#include <filesystem>

#include "checkpoint.h"
#include "fuzz_support.h"
#include "model_impl.h"

namespace pixelcloth::fuzz {

inline learn::ModelSpec fuzzSpec() {
  learn::ModelSpec spec;
  spec.architecture = learn::Architecture::FullyConnected;
  spec.width = 0.05;
  spec.inputSize = 4;
  spec.outputValues = 6;
  return spec;
}

}  // namespace pixelcloth::fuzz
