// Lines cut into a finished garment mesh: edges split with their UVs, seams, openings and cage lines kept consistent,
// and straight pattern lines made chains of mesh edges without sliver triangles.
#include "pixelcloth/garment/pattern_lines.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "support/fixtures.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
namespace pg = pixelcloth::garment;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

namespace {

const pg::Garment& necktie() {
  static const pg::Garment tie = pg::makeNecktie();
  return tie;
}

Eigen::Vector2d uvOf(const pg::Garment& g, int v, int layout) { return g.mesh.UV.row(g.vertexUV(v, layout)); }

/// Signed pattern-space area of face f in its layout.
double uvArea(const pg::Garment& g, int f) {
  const Eigen::Vector2d a = g.mesh.UV.row(g.mesh.FUV(f, 0)), b = g.mesh.UV.row(g.mesh.FUV(f, 1)),
                        c = g.mesh.UV.row(g.mesh.FUV(f, 2));
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

double totalUvArea(const pg::Garment& g) {
  double sum = 0;
  for (int f = 0; f < g.mesh.numFaces(); ++f) sum += uvArea(g, f);
  return sum;
}

bool sharesEdge(const pg::Garment& g, int a, int b) {
  for (int f = 0; f < g.mesh.numFaces(); ++f) {
    int hits = 0;
    for (int k = 0; k < 3; ++k) hits += g.mesh.F(f, k) == a || g.mesh.F(f, k) == b;
    if (hits == 2) return true;
  }
  return false;
}

/// The outline vertex of layout 0 nearest `uv`.
int outlineVertexNear(const pg::Garment& g, const Eigen::Vector2d& uv) {
  int best = -1;
  for (int v : g.openings.front().vertices)
    if (best < 0 || (uvOf(g, v, 0) - uv).norm() < (uvOf(g, best, 0) - uv).norm()) best = v;
  return best;
}

}  // namespace

TEST(PatternLines, SplittingAnEdgeOnAStitchedSeamAddsOneVertexWithAUvInBothLayouts) {
  pg::Garment g = pixelcloth::testing::tshirt();
  const pg::Seam& side = *g.findSeam("side_left");
  const int a = side.vertices[3], b = side.vertices[4];
  const int faces = g.mesh.numFaces(), vertices = g.mesh.numVertices();
  const double area = totalUvArea(g);
  const int n = pg::splitEdge(g, a, b, 0.4);
  EXPECT_EQ(n, vertices);
  EXPECT_EQ(g.mesh.numFaces(), faces + 2);  // one face on each side of the seam
  for (int layout : {0, 1}) {
    ASSERT_GE(g.vertexUV(n, layout), 0);
    EXPECT_LT((uvOf(g, n, layout) - (0.6 * uvOf(g, a, layout) + 0.4 * uvOf(g, b, layout))).norm(), 1e-12);
  }
  EXPECT_LT((g.mesh.V.row(n) - (0.6 * g.mesh.V.row(a) + 0.4 * g.mesh.V.row(b))).norm(), 1e-12);
  const std::vector<int>& chain = g.findSeam("side_left")->vertices;
  EXPECT_EQ(chain[4], n);
  EXPECT_EQ(chain[5], b);
  EXPECT_NEAR(totalUvArea(g), area, 1e-12);
  for (int f = 0; f < g.mesh.numFaces(); ++f) EXPECT_GT(uvArea(g, f), 0) << "face " << f;
  EXPECT_TRUE(g.recipe.is_null());  // no longer the template's exact mesh
}

TEST(PatternLines, ALineAcrossTheTieIsAChainOfMeshEdgesAndTheGarmentStaysValid) {
  pg::Garment g = necktie();
  const Eigen::AlignedBox2d box = g.layoutBounds(0);
  const double v = box.min().y() + 0.55 * box.sizes().y();
  const int from = outlineVertexNear(g, {box.min().x(), v}), to = outlineVertexNear(g, {box.max().x(), v});
  const double area = totalUvArea(g), angleBefore = pg::smallestPatternAngleDegrees(g);
  const std::vector<int> chain = pg::insertPatternLine(g, 0, from, to);
  ASSERT_GE(chain.size(), 3u);
  EXPECT_EQ(chain.front(), from);
  EXPECT_EQ(chain.back(), to);
  for (size_t k = 0; k + 1 < chain.size(); ++k) EXPECT_TRUE(sharesEdge(g, chain[k], chain[k + 1])) << k;
  // Every chain vertex on the straight line, or a vertex taken within the snap of an edge (about 2 mm here).
  const Eigen::Vector2d p = uvOf(g, from, 0), d = (uvOf(g, to, 0) - p).normalized();
  for (int w : chain) {
    const Eigen::Vector2d q = uvOf(g, w, 0) - p;
    EXPECT_LT(std::abs(q.x() * d.y() - q.y() * d.x()), 0.005) << "vertex " << w;
  }
  EXPECT_NEAR(totalUvArea(g), area, 1e-12);
  for (int f = 0; f < g.mesh.numFaces(); ++f) EXPECT_GT(uvArea(g, f), 0) << "face " << f;
  // No sliver triangles: crossings near a vertex take the vertex.
  EXPECT_GT(pg::smallestPatternAngleDegrees(g), std::min(angleBefore, 6.0));

  g.lines.push_back(pg::CageLine{"tie_cut", pg::CurveKind::Split, chain, false});
  g.lines.erase(std::remove_if(g.lines.begin(), g.lines.end(),
                               [](const pg::CageLine& line) { return line.name != "tie_cut"; }),
                g.lines.end());
  // Saved and read back, it passes every check importGarment makes (closed patches, chains along mesh edges).
  const fs::path dir = freshDir("tie");
  pg::saveGarment(dir, g);
  const pg::Garment loaded = pg::loadGarment(dir);
  EXPECT_EQ(loaded.mesh.numVertices(), g.mesh.numVertices());
  EXPECT_EQ(loaded.findLine("tie_cut")->vertices, chain);
}

TEST(PatternLines, FlipsFattenThinTrianglesWithoutMovingAVertexOrCrossingACurve) {
  pg::Garment g = necktie();
  const Eigen::AlignedBox2d box = g.layoutBounds(0);
  // A line nearly along the blade, so that it crosses many edges at shallow angles.
  const int from = outlineVertexNear(g, {box.min().x(), box.min().y() + 0.3 * box.sizes().y()});
  const int to = outlineVertexNear(g, {box.max().x(), box.min().y() + 0.7 * box.sizes().y()});
  const std::vector<int> chain = pg::insertPatternLine(g, 0, from, to);
  g.lines = {pg::CageLine{"cut", pg::CurveKind::Split, chain, false}};
  const double before = pg::smallestPatternAngleDegrees(g), area = totalUvArea(g);
  const Eigen::MatrixX3d V = g.mesh.V;
  const int flips = pg::flipThinTriangles(g);
  EXPECT_GT(flips, 0);
  EXPECT_GT(pg::smallestPatternAngleDegrees(g), before);
  EXPECT_EQ(g.mesh.V, V);  // no vertex moved
  EXPECT_NEAR(totalUvArea(g), area, 1e-12);
  for (int f = 0; f < g.mesh.numFaces(); ++f) EXPECT_GT(uvArea(g, f), 0) << "face " << f;
  for (size_t k = 0; k + 1 < chain.size(); ++k) EXPECT_TRUE(sharesEdge(g, chain[k], chain[k + 1])) << k;
  // Still a valid garment: saved and read back through every check of the import.
  const fs::path dir = freshDir("flipped");
  pg::saveGarment(dir, g);
  EXPECT_EQ(pg::loadGarment(dir).mesh.numFaces(), g.mesh.numFaces());
}

TEST(PatternLines, ALineThatLeavesItsLayoutOrAnEdgeThatIsNoneIsRefused) {
  pg::Garment g = pixelcloth::testing::tshirt();
  // From the far end of the left sleeve to the hem's left corner: the straight line passes outside the armpit.
  int sleeveEnd = -1, hemCorner = -1;
  for (int v = 0; v < g.mesh.numVertices(); ++v) {
    if (g.vertexUV(v, 0) < 0) continue;
    const Eigen::Vector2d uv = uvOf(g, v, 0);
    if (sleeveEnd < 0 || uv.x() > uvOf(g, sleeveEnd, 0).x()) sleeveEnd = v;
    if (hemCorner < 0 || uv.x() - 4 * uv.y() > uvOf(g, hemCorner, 0).x() - 4 * uvOf(g, hemCorner, 0).y()) hemCorner = v;
  }
  const std::string message = inputErrorOf([&] { pg::insertPatternLine(g, 0, sleeveEnd, hemCorner); });
  EXPECT_NE(message.find("leaves layout front"), std::string::npos) << message;

  const std::string noEdge = inputErrorOf([&] { pg::splitEdge(g, 0, g.mesh.numVertices() - 1, 0.5); });
  EXPECT_NE(noEdge.find("is no edge of the mesh"), std::string::npos) << noEdge;
  EXPECT_NE(inputErrorOf([&] { pg::splitEdge(g, g.mesh.F(0, 0), g.mesh.F(0, 1), 1.0); }).find("expected 0 < t < 1"),
            std::string::npos);
}
