// core::readExr (OpenEXR's reader, behind our own checks) and the cloth image reader on top of it.
#include "fuzz_support.h"
#include "pixelcloth/core/exr_io.h"
#include "pixelcloth/patches/cloth_image.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* out = pixelcloth::fuzz::seedOut()) {
    // An 8 x 6 one-layout cloth image: du dv dn and the mask, as the images verb writes them (at full size).
    pixelcloth::core::ExrImage image;
    for (const char* name : {"du", "dv", "dn", "mask"})
      image.addChannel(name, Eigen::MatrixXf::Constant(6, 8, name[0] == 'm' ? 1.0f : 0.01f));
    pixelcloth::core::writeExr(std::filesystem::path(out) / "cloth_8x6.exr", image);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("input.exr", data, size);
  pixelcloth::fuzz::guarded([&] { pixelcloth::core::readExr(path); });
  return pixelcloth::fuzz::guarded([&] { pixelcloth::patches::readClothImage(path); });
}
