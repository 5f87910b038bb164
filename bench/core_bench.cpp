// Micro benchmarks for core/ (Google Benchmark). End-to-end goals live in `pixelcloth bench`.
#include <benchmark/benchmark.h>

#include "pixelcloth/core/mesh.h"

static void BM_VertexNormals(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Eigen::MatrixX3d V = Eigen::MatrixX3d::Random(n * n, 3);
  Eigen::MatrixX3i F(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      F.row(f++) << i * n + j, i * n + j + 1, (i + 1) * n + j;
      F.row(f++) << i * n + j + 1, (i + 1) * n + j + 1, (i + 1) * n + j;
    }
  for (auto _ : state) benchmark::DoNotOptimize(pixelcloth::core::vertexNormals(V, F));
}
BENCHMARK(BM_VertexNormals)->Arg(128);
