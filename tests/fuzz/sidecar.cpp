// A model folder's model.json, as learn's loader reads it (core::readJson, then the spec it describes).
#include "checkpoint.h"
#include "fuzz_support.h"
#include "pixelcloth/core/json_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("model.json", data, size);
  return pixelcloth::fuzz::guarded([&] {
    const pixelcloth::learn::ModelSpec spec = pixelcloth::learn::specOfSidecar(pixelcloth::core::readJson(path), path.string());
    pixelcloth::learn::summarize(spec);
  });
}
