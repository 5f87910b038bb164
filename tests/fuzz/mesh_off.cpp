// core::readMesh on a .off file (OpenMesh's reader, behind our own checks).
#include "seed_mesh.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  pixelcloth::fuzz::writeMeshSeed("off");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("input.off", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::core::readMesh(path); });
}
