// core::readPng (libpng, behind our own checks).
#include "fuzz_support.h"
#include "pixelcloth/core/image.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* out = pixelcloth::fuzz::seedOut()) {
    pixelcloth::core::RgbImage image(8, 6, {200, 100, 50});
    *image.at(3, 2) = 0;
    pixelcloth::core::writePng(std::filesystem::path(out) / "rgb_8x6.png", image);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("input.png", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::core::readPng(path); });
}
