// core::readMesh on a .ply file (OpenMesh's reader, behind our own checks).
#include "seed_mesh.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  pixelcloth::fuzz::writeMeshSeed("ply");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("input.ply", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::core::readMesh(path); });
}
