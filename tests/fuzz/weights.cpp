// learn::loadWeights: a model.tensors (a pixelcloth tensor file, core/tensor_file.h) loaded into a known network.
#include "fuzz_network.h"
#include "fuzz_support.h"

namespace {
pixelcloth::learn::Model& model() {
  static pixelcloth::learn::Model m(pixelcloth::fuzz::fuzzSpec(), 1);
  return m;
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  torch::set_num_threads(1);
  if (const char* out = pixelcloth::fuzz::seedOut()) {
    const std::filesystem::path seed = std::filesystem::path(out) / "model.tensors";
    pixelcloth::learn::saveWeights(pixelcloth::learn::ModelAccess::network(model()), seed);
    pixelcloth::fuzz::writeDeepMetaSeed(seed, "weights");
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("model.tensors", data, size);
  return pixelcloth::fuzz::guarded(
      [&] { pixelcloth::learn::loadWeights(pixelcloth::learn::ModelAccess::network(model()), path, "the fuzz network"); });
}
