// core::readMesh on a .obj file (OpenMesh's reader, behind our own checks).
#include "seed_mesh.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  pixelcloth::fuzz::writeMeshSeed("obj");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("input.obj", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::core::readMesh(path); });
}
