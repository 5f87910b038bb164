// core::readNpy and the matrix reader the datasets use.
#include "fuzz_support.h"
#include "pixelcloth/core/npy.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* out = pixelcloth::fuzz::seedOut()) {
    const std::filesystem::path folder(out);
    const Eigen::MatrixXf matrix = Eigen::MatrixXf::Constant(3, 4, 0.5f);
    pixelcloth::core::writeNpy(folder / "float32_3x4.npy", matrix);
    pixelcloth::core::writeNpy(folder / "uint8_5.npy", std::vector<std::uint8_t>{0, 1, 2, 1, 0}, {5});
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("input.npy", data, size);
  pixelcloth::fuzz::guarded([&] { pixelcloth::core::readNpy(path); });
  return pixelcloth::fuzz::guarded([&] { pixelcloth::core::readNpyMatrixF(path); });
}
