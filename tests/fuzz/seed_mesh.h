#pragma once

// The mesh targets' seed: a unit octahedron with per-corner UVs (on the OBJ) and a vertex attribute, written by
// core::writeMesh.

#include <filesystem>

#include "fuzz_support.h"
#include "pixelcloth/core/mesh_io.h"

namespace pixelcloth::fuzz {

inline void writeMeshSeed(const char* extension) {
  const char* out = seedOut();
  if (!out) return;
  core::Mesh mesh;
  mesh.V.resize(6, 3);
  mesh.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  mesh.F.resize(8, 3);
  mesh.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  if (std::string(extension) == "obj") {
    mesh.UV.resize(4, 2);
    mesh.UV << 0, 0, 1, 0, 1, 1, 0, 1;
    mesh.FUV.resize(8, 3);
    for (int f = 0; f < 8; ++f) mesh.FUV.row(f) << f % 4, (f + 1) % 4, (f + 2) % 4;
  }
  writeMesh(std::filesystem::path(out) / (std::string("octahedron.") + extension), mesh);
}

}  // namespace pixelcloth::fuzz
