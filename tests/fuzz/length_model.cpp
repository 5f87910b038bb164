// cage::readLengthModel: a worn-length model file.
#include "fuzz_support.h"
#include "pixelcloth/cage/length_model.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("length_model.json", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::cage::readLengthModel(path); });
}
