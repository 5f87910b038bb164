// Garment shapes compared through the sewing pattern: two meshes of one pattern agree where their shapes agree and
// differ by a known shift; one mesh compares vertex by vertex; garments of other patterns are refused.
#include "pixelcloth/sim/shape_comparison.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pixelcloth/core/error.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::sim {
namespace {

/// A smooth surface over the pattern: each vertex placed at its UV (of the first layout that holds it) lifted by a
/// bump, the back layout 5 cm behind the front. Both meshes of the pattern sample the same surface.
Eigen::MatrixX3d patternSurface(const garment::Garment& g) {
  Eigen::MatrixX3d x(g.mesh.numVertices(), 3);
  for (int v = 0; v < g.mesh.numVertices(); ++v) {
    int layout = 0;
    while (g.vertexUV(v, layout) < 0) ++layout;
    const Eigen::Vector2d uv = g.uvOf(v, layout);
    x.row(v) << uv.x(), uv.y(), 0.02 * std::sin(6 * uv.x()) * std::cos(4 * uv.y()) - 0.05 * layout;
  }
  return x;
}

TEST(ShapeComparison, TwoMeshesOfOnePatternAgreeThroughThePatternAndSeeAShift) {
  garment::TShirtOptions coarse, fine;
  coarse.targetVertices = 1200;
  fine.targetVertices = 2000;
  const garment::Garment a = garment::makeTShirt(coarse), b = garment::makeTShirt(fine);
  ASSERT_NE(a.mesh.numVertices(), b.mesh.numVertices());
  const Eigen::MatrixX3d xa = patternSurface(a), xb = patternSurface(b);
  // Away from the side seams (where the surface jumps between the layouts) the two agree to the image's resolution.
  const Eigen::VectorXd same = distancesThroughPattern(a, xa, b, xb);
  ASSERT_EQ(same.size(), b.mesh.numVertices());
  std::vector<double> sorted;
  for (int v = 0; v < same.size(); ++v)
    if (std::isfinite(same(v))) sorted.push_back(same(v));
  ASSERT_GT(sorted.size(), 0.95 * b.mesh.numVertices());
  std::sort(sorted.begin(), sorted.end());
  EXPECT_LT(sorted[sorted.size() / 2], 0.001);  // median below 1 mm
  Eigen::MatrixX3d shifted = xb;
  shifted.col(2).array() += 0.01;
  const Eigen::VectorXd apart = distancesThroughPattern(a, xa, b, shifted);
  int near = 0, counted = 0;
  for (int v = 0; v < apart.size(); ++v)
    if (std::isfinite(apart(v)) && same(v) < 0.001) ++counted, near += std::abs(apart(v) - 0.01) < 0.001;
  EXPECT_GT(near, 0.99 * counted);
}

TEST(ShapeComparison, OneMeshComparesVertexByVertexAndOtherPatternsAreRefused) {
  const garment::Garment shirt = garment::makeTShirt(), tie = garment::makeNecktie();
  Eigen::MatrixX3d x = shirt.mesh.V, y = x;
  y(7, 1) += 0.03;
  const Eigen::VectorXd d = distancesThroughPattern(shirt, x, shirt, y);
  EXPECT_NEAR(d(7), 0.03, 1e-12);
  EXPECT_EQ(d.maxCoeff(), d(7));
  EXPECT_THROW(distancesThroughPattern(shirt, x, tie, tie.mesh.V), core::InputError);
  EXPECT_THROW(distancesThroughPattern(shirt, x.topRows(10), shirt, y), core::InputError);
}

}  // namespace
}  // namespace pixelcloth::sim
