// Micro benchmarks for patches/ (Google Benchmark): building and applying the blendshape bases.
#include <benchmark/benchmark.h>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/basis.h"

namespace {
namespace pp = pixelcloth::patches;

/// The built-in T-shirt cut along its cage: its 28 patches.
const std::vector<pp::PatchMesh>& shirtPatches() {
  static const std::vector<pp::PatchMesh> meshes = [] {
    const pixelcloth::garment::Garment shirt = pixelcloth::garment::makeTShirt();
    std::vector<pp::PatchMesh> out;
    for (const pp::Patch& p :
         pp::garmentPatches(shirt))
      out.push_back(pp::patchMesh(shirt, p));
    return out;
  }();
  return meshes;
}

/// 28 synthetic patches of 113 to 145 vertices (7 x 7 to 8 x 8 square cells of 2 cm).
const std::vector<pp::PatchMesh>& syntheticPatches() {
  static const std::vector<pp::PatchMesh> meshes = [] {
    std::vector<pp::PatchMesh> out;
    for (int k = 0; k < 28; ++k) {
      int nu = 7 + k % 2, nv = 7 + (k / 2) % 2;
      out.push_back(pp::rectanglePatch(0.02 * nu, 0.02 * nv, nu, nv));
    }
    return out;
  }();
  return meshes;
}

pp::BasisOptions options(bool anisotropic) {
  pp::BasisOptions o;
  o.anisotropic = anisotropic;
  o.theta = 0.5;
  o.ratio = 0.1;
  return o;
}
}  // namespace

static void BM_BasesShirt28(benchmark::State& state) {
  for (auto _ : state)
    for (const pp::PatchMesh& patch : shirtPatches())
      benchmark::DoNotOptimize(pp::PatchBasis(patch, options(state.range(0))));
}
BENCHMARK(BM_BasesShirt28)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

static void BM_BasesSynthetic28(benchmark::State& state) {
  for (auto _ : state)
    for (const pp::PatchMesh& patch : syntheticPatches())
      benchmark::DoNotOptimize(pp::PatchBasis(patch, options(state.range(0))));
}
BENCHMARK(BM_BasesSynthetic28)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

/// One fill (#interior x #boundary times #boundary x 3): arg 0..5 one of the first T-shirt patches, 6 a synthetic
/// 145-vertex patch.
static void BM_Fill(benchmark::State& state) {
  const pp::PatchMesh& patch = state.range(0) < 6 ? shirtPatches()[state.range(0)] : syntheticPatches()[3];
  pp::PatchBasis basis(patch);
  Eigen::MatrixX3d data = Eigen::MatrixX3d::Random(patch.boundary.size(), 3);
  for (auto _ : state) benchmark::DoNotOptimize(basis.fill(data));
  state.SetLabel(std::to_string(patch.uv.rows()) + " vertices, " + std::to_string(patch.boundary.size()) + " boundary");
}
BENCHMARK(BM_Fill)->DenseRange(0, 6)->Unit(benchmark::kMicrosecond);
