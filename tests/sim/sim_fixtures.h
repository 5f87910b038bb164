#pragma once
// Small cloth and collider meshes for the solver tests.

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "pixelcloth/core/mesh.h"
#include "pixelcloth/sim/quasistatic.h"

namespace pixelcloth::sim::fixtures {

/// A square sheet of side `size` with n x n vertices, lying in the plane y = height, pattern = its flat layout. The
/// diagonals mirror at x = 0 and z = 0, so the triangulation is as symmetric as the square.
inline core::Mesh sheet(int n, double size, double height) {
  core::Mesh mesh;
  mesh.V.resize(n * n, 3);
  mesh.UV.resize(n * n, 2);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = size * j / (n - 1) - size / 2, v = size * i / (n - 1) - size / 2;
      mesh.V.row(i * n + j) << u, height, v;
      mesh.UV.row(i * n + j) << u, v;
    }
  mesh.F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + 1, c = a + n, d = c + 1;
      if ((2 * j < n - 1) == (2 * i < n - 1)) {
        mesh.F.row(f++) << a, c, b;
        mesh.F.row(f++) << b, c, d;
      } else {
        mesh.F.row(f++) << a, c, d;
        mesh.F.row(f++) << a, d, b;
      }
    }
  mesh.FUV = mesh.F;
  return mesh;
}

/// A UV sphere (closed, outward faces) of radius r centred at the origin.
inline Collider sphere(double r, int rings = 24, int segments = 48) {
  Collider s;
  s.V.resize(2 + (rings - 1) * segments, 3);
  s.V.row(0) << 0, r, 0;
  s.V.row(1) << 0, -r, 0;
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double theta = M_PI * i / rings, phi = 2 * M_PI * j / segments;
      s.V.row(2 + (i - 1) * segments + j) << r * std::sin(theta) * std::cos(phi), r * std::cos(theta),
          r * std::sin(theta) * std::sin(phi);
    }
  std::vector<Eigen::Vector3i> faces;
  auto ring = [&](int i, int j) { return 2 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    faces.emplace_back(0, ring(1, j + 1), ring(1, j));
    faces.emplace_back(1, ring(rings - 1, j), ring(rings - 1, j + 1));
    for (int i = 1; i + 1 < rings; ++i) {
      faces.emplace_back(ring(i, j), ring(i, j + 1), ring(i + 1, j));
      faces.emplace_back(ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j));
    }
  }
  s.F.resize(static_cast<int>(faces.size()), 3);
  for (int f = 0; f < s.F.rows(); ++f) s.F.row(f) = faces[f].transpose();
  return s;
}

}  // namespace pixelcloth::sim::fixtures
