// Private to sim/: the flat pattern as the rest shape of both cloth solvers.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh.h"

namespace pixelcloth::sim::detail {

/// Per triangle of the cloth, the rest shape its pattern coordinates (UV, metres) give: the gradient operator G (2 x 3,
/// so that the deformation gradient of corners X, 3 x 3 rows, is (G X)^T) and the area; per vertex, a third of the
/// areas of its triangles.
struct PatternTriangles {
  std::vector<Eigen::Matrix<double, 2, 3>> G;
  Eigen::VectorXd area;
  Eigen::VectorXd vertexArea;
};

/// Throws InputError for a missing pattern, a degenerate pattern triangle or a vertex in no triangle (counted from 1).
inline PatternTriangles patternTriangles(const core::Mesh& cloth) {
  PIXELCLOTH_CHECK(cloth.hasUV(), "solver: the cloth mesh needs per-corner pattern coordinates (UV) as rest shape");
  const int n = cloth.numVertices(), m = cloth.numFaces();
  PatternTriangles p;
  p.G.resize(m);
  p.area.resize(m);
  p.vertexArea = Eigen::VectorXd::Zero(n);
  Eigen::Matrix<double, 2, 3> edges;
  edges << -1, 1, 0, -1, 0, 1;
  for (int f = 0; f < m; ++f) {
    Eigen::Vector2d u[3];
    for (int k = 0; k < 3; ++k) u[k] = cloth.UV.row(cloth.FUV(f, k)).transpose();
    Eigen::Matrix2d Dm;
    Dm.col(0) = u[1] - u[0];
    Dm.col(1) = u[2] - u[0];
    const double area = 0.5 * std::abs(Dm.determinant());
    PIXELCLOTH_CHECK(area > 1e-12, "solver: pattern triangle " << f + 1 << " is degenerate (area " << area << " m^2)");
    p.area(f) = area;
    p.G[f] = Dm.inverse().transpose() * edges;
    for (int a = 0; a < 3; ++a) p.vertexArea(cloth.F(f, a)) += area / 3.0;
  }
  for (int v = 0; v < n; ++v)
    PIXELCLOTH_CHECK(p.vertexArea(v) > 0, "solver: cloth vertex " << v + 1 << " belongs to no triangle");
  return p;
}

}  // namespace pixelcloth::sim::detail
