// Garment templates: the T-shirt and necktie patterns, their meshing, stitching, placement and picture.
#include "pixelcloth/garment/garment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <set>
#include <unordered_set>

#include "pixelcloth/core/edge_key.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/core/mesh.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;

namespace {
const pixelcloth::garment::Garment& shirt() { return pixelcloth::testing::tshirt(); }

const pg::Garment& tie() {
  static const pg::Garment garment = pg::makeNecktie();
  return garment;
}

using pixelcloth::core::edgeKey;

/// Undirected edges of the faces of one layout.
std::unordered_set<std::uint64_t> layoutEdges(const pg::Garment& g, int layout) {
  std::unordered_set<std::uint64_t> edges;
  for (int f = 0; f < g.mesh.numFaces(); ++f) {
    if (g.faceLayout[f] != layout) continue;
    for (int k = 0; k < 3; ++k) edges.insert(edgeKey(g.mesh.F(f, k), g.mesh.F(f, (k + 1) % 3)));
  }
  return edges;
}

/// Length of a chain measured in one layout's UVs.
double uvLength(const pg::Garment& g, const std::vector<int>& chain, int layout) {
  double total = 0;
  for (size_t i = 0; i + 1 < chain.size(); ++i) {
    Eigen::Vector2d a = g.mesh.UV.row(g.vertexUV(chain[i], layout)),
                    b = g.mesh.UV.row(g.vertexUV(chain[i + 1], layout));
    total += (b - a).norm();
  }
  return total;
}

double minAngleDegrees(const pg::Garment& g) {
  double smallest = 180;
  for (int f = 0; f < g.mesh.numFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector2d p = g.mesh.UV.row(g.mesh.FUV(f, k)), a = g.mesh.UV.row(g.mesh.FUV(f, (k + 1) % 3)),
                      b = g.mesh.UV.row(g.mesh.FUV(f, (k + 2) % 3));
      double c = (a - p).normalized().dot((b - p).normalized());
      smallest = std::min(smallest, std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI);
    }
  }
  return smallest;
}

/// Checks the structural invariants every garment template must satisfy.
void expectWellFormed(const pg::Garment& g) {
  ASSERT_NO_THROW(g.mesh.validate(g.name));
  ASSERT_TRUE(g.mesh.hasUV());
  ASSERT_EQ(g.faceLayout.size(), g.mesh.numFaces());
  ASSERT_EQ(g.facePanel.size(), g.mesh.numFaces());
  ASSERT_EQ(g.vertexUV.rows(), g.mesh.numVertices());
  ASSERT_EQ(g.vertexUV.cols(), g.numLayouts());
  for (int f = 0; f < g.mesh.numFaces(); ++f) {
    ASSERT_GE(g.faceLayout[f], 0);
    ASSERT_LT(g.faceLayout[f], g.numLayouts());
    ASSERT_GE(g.facePanel[f], 0);
    ASSERT_LT(g.facePanel[f], static_cast<int>(g.panels.size()));
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(g.vertexUV(g.mesh.F(f, k), g.faceLayout[f]), g.mesh.FUV(f, k)) << "face " << f;
  }
  // Every vertex has a UV in at least one layout.
  for (int v = 0; v < g.mesh.numVertices(); ++v) ASSERT_GE(g.vertexUV.row(v).maxCoeff(), 0) << "vertex " << v;
}

/// Openings are exactly the boundary: each opening edge is a boundary edge and there are no others.
void expectBoundaryIsOpenings(const pg::Garment& g) {
  pc::TopologyReport report = pc::checkTopology(g.mesh.numVertices(), g.mesh.F);
  EXPECT_EQ(report.nonManifoldEdges, 0) << report.firstProblem;
  EXPECT_EQ(report.inconsistentEdges, 0) << report.firstProblem;
  EXPECT_EQ(report.nonManifoldVertices, 0) << report.firstProblem;
  EXPECT_EQ(report.isolatedVertices, 0);
  EXPECT_EQ(report.components, 1);
  std::unordered_set<std::uint64_t> allEdges;
  std::map<std::uint64_t, int> uses;
  for (int f = 0; f < g.mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k) ++uses[edgeKey(g.mesh.F(f, k), g.mesh.F(f, (k + 1) % 3))];
  int openingEdges = 0;
  std::set<int> openingVertices;
  for (const auto& opening : g.openings) {
    const size_t n = opening.vertices.size();
    ASSERT_GE(n, 3u) << opening.name;
    for (size_t i = 0; i < n; ++i) {
      EXPECT_TRUE(openingVertices.insert(opening.vertices[i]).second) << opening.name << " repeats or shares a vertex";
      EXPECT_EQ(uses[edgeKey(opening.vertices[i], opening.vertices[(i + 1) % n])], 1)
          << opening.name << ": edge " << i << " is not a boundary edge";
      ++openingEdges;
    }
  }
  EXPECT_EQ(report.boundaryEdges, openingEdges) << "boundary edges that belong to no opening";
}

}  // namespace

TEST(TShirt, VertexCountNearTarget) {
  const pg::Garment& g = shirt();
  std::cout << "[ tshirt   ] " << g.summary() << "\n[ tshirt   ] " << g.meshing.summary(g.mesh.numVertices())
            << std::endl;
  EXPECT_NEAR(g.mesh.numVertices(), 3000, 300);
  EXPECT_GT(g.meshing.seconds, 0.0);  // recorded; its speed is `pixelcloth bench`'s garment.tshirt_build
  pg::TShirtOptions dense;
  dense.targetVertices = 6000;
  EXPECT_NEAR(pg::makeTShirt(dense).mesh.numVertices(), 6000, 600);
}

TEST(TShirt, IsWellFormed) {
  expectWellFormed(shirt());
  EXPECT_EQ(shirt().layouts, (std::vector<std::string>{"front", "back"}));
  EXPECT_EQ(shirt().panels.size(), 6u);
  // Every panel has faces, all in its own layout (panels alternate front, back).
  for (int p = 0; p < 6; ++p) {
    int count = 0;
    for (int f = 0; f < shirt().mesh.numFaces(); ++f) {
      if (shirt().facePanel[f] != p) continue;
      ++count;
      EXPECT_EQ(shirt().faceLayout[f], p % 2) << shirt().panels[p];
    }
    EXPECT_GT(count, 50) << shirt().panels[p];
  }
}

TEST(TShirt, LengthAndSize) {
  const pg::Garment& g = shirt();
  EXPECT_NEAR(g.length(), 0.67, 0.01);
  for (int l = 0; l < 2; ++l) {
    Eigen::AlignedBox2d box = g.layoutBounds(l);
    EXPECT_NEAR(box.sizes().y(), 0.67, 0.01) << g.layouts[l];
    EXPECT_NEAR(box.sizes().x(), 2 * (0.20 + 0.21), 1e-9) << "sleeve end to sleeve end";
    EXPECT_NEAR(box.center().x(), 0, 1e-12);
  }
  // Rest placement: neck-side point at ~1.48 m, hem at ~0.81 m, centred on x = 0.
  Eigen::Vector3d lo = g.mesh.V.colwise().minCoeff(), hi = g.mesh.V.colwise().maxCoeff();
  EXPECT_NEAR(hi.y(), 1.48, 0.01);
  EXPECT_NEAR(lo.y(), 0.81, 0.01);
  EXPECT_NEAR(lo.x() + hi.x(), 0, 1e-9);
  EXPECT_NEAR(hi.z(), 0.12, 0.005);
  EXPECT_NEAR(lo.z(), -0.12, 0.005);
}

TEST(TShirt, StitchedSeamsShareVerticesOnBothLayouts) {
  const pg::Garment& g = shirt();
  auto front = layoutEdges(g, 0), back = layoutEdges(g, 1);
  int stitched = 0;
  for (const auto& seam : g.seams) {
    if (!seam.joinsLayouts) continue;
    ++stitched;
    ASSERT_GE(seam.vertices.size(), 2u) << seam.name;
    for (size_t i = 0; i + 1 < seam.vertices.size(); ++i) {
      auto e = edgeKey(seam.vertices[i], seam.vertices[i + 1]);
      EXPECT_TRUE(front.count(e)) << seam.name << ": edge " << i << " is not in a front face";
      EXPECT_TRUE(back.count(e)) << seam.name << ": edge " << i << " is not in a back face";
    }
    for (int v : seam.vertices) {
      ASSERT_GE(g.vertexUV(v, 0), 0) << seam.name;
      ASSERT_GE(g.vertexUV(v, 1), 0) << seam.name;
      EXPECT_DOUBLE_EQ(g.mesh.V(v, 2), 0.0) << seam.name << ": seam vertices lie in the plane z = 0";
    }
    double frontLength = uvLength(g, seam.vertices, 0), backLength = uvLength(g, seam.vertices, 1);
    EXPECT_NEAR(frontLength, backLength, 1e-6 * frontLength) << seam.name;
  }
  EXPECT_EQ(stitched, 8);
  for (const char* name : {"side_left", "side_right", "underarm_left", "underarm_right", "shoulder_left",
                           "shoulder_right", "sleeve_top_left", "sleeve_top_right"}) {
    ASSERT_NE(g.findSeam(name), nullptr) << name;
    EXPECT_TRUE(g.findSeam(name)->joinsLayouts) << name;
  }
  // The side seam runs from the armpit to the hem: length - armpitDepth in both layouts.
  const pg::TShirtOptions options;
  EXPECT_NEAR(uvLength(g, g.findSeam("side_left")->vertices, 0), options.length - options.armpitDepth, 1e-9);
}

TEST(TShirt, ArmholesAreEdgeChainsInsideOneLayout) {
  const pg::Garment& g = shirt();
  for (const char* name : {"armhole_front_left", "armhole_front_right", "armhole_back_left", "armhole_back_right"}) {
    const pg::Seam* seam = g.findSeam(name);
    ASSERT_NE(seam, nullptr) << name;
    EXPECT_FALSE(seam->joinsLayouts);
    const int layout = std::string(name).find("front") != std::string::npos ? 0 : 1;
    auto edges = layoutEdges(g, layout);
    ASSERT_GE(seam->vertices.size(), 3u);
    for (size_t i = 0; i + 1 < seam->vertices.size(); ++i) {
      EXPECT_TRUE(edges.count(edgeKey(seam->vertices[i], seam->vertices[i + 1]))) << name << ": edge " << i;
    }
    // Interior vertices of an armhole belong to its layout only, with body on one side and sleeve on the other.
    for (size_t i = 1; i + 1 < seam->vertices.size(); ++i) {
      EXPECT_EQ(g.vertexUV(seam->vertices[i], 1 - layout), -1) << name;
    }
  }
}

TEST(TShirt, PatternTrianglesAreWellShapedAndCounterClockwise) {
  const pg::Garment& g = shirt();
  double smallest = minAngleDegrees(g);
  std::cout << "[ tshirt   ] min angle " << smallest << " deg" << std::endl;
  EXPECT_GE(smallest, 20.0);
  EXPECT_NEAR(g.meshing.minAngleDegrees, smallest, 1e-9);
  for (int f = 0; f < g.mesh.numFaces(); ++f) {
    Eigen::Vector2d a = g.mesh.UV.row(g.mesh.FUV(f, 0)), b = g.mesh.UV.row(g.mesh.FUV(f, 1)),
                    c = g.mesh.UV.row(g.mesh.FUV(f, 2));
    double twiceArea = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    ASSERT_GT(twiceArea, 0) << "face " << f << " of layout " << g.faceLayout[f];
  }
}

TEST(TShirt, BoundaryIsTheFourOpenings) {
  const pg::Garment& g = shirt();
  ASSERT_EQ(g.openings.size(), 4u);
  std::set<std::string> names;
  for (const auto& o : g.openings) names.insert(o.name);
  EXPECT_EQ(names, (std::set<std::string>{"hem", "neckline", "sleeve_hem_left", "sleeve_hem_right"}));
  expectBoundaryIsOpenings(g);
}

TEST(TShirt, NormalsPointAwayFromTheBody) {
  const pg::Garment& g = shirt();
  Eigen::MatrixX3d N = pc::faceNormals(g.mesh.V, g.mesh.F);
  for (int f = 0; f < g.mesh.numFaces(); ++f) {
    if (g.faceLayout[f] == 0) {
      ASSERT_GT(N(f, 2), 0) << "front face " << f;
    } else {
      ASSERT_LT(N(f, 2), 0) << "back face " << f;
    }
  }
}

TEST(TShirt, FrontNecklineIsDeeperThanBack) {
  const pg::Garment& g = shirt();
  const pg::Opening& neck = g.openings[1];
  ASSERT_EQ(neck.name, "neckline");
  double frontLowest = 10, backLowest = 10;
  for (int v : neck.vertices) {
    if (g.vertexUV(v, 0) >= 0) frontLowest = std::min(frontLowest, g.mesh.V(v, 1));
    if (g.vertexUV(v, 1) >= 0) backLowest = std::min(backLowest, g.mesh.V(v, 1));
  }
  EXPECT_NEAR(1.48 - frontLowest, 0.09, 0.005);
  EXPECT_NEAR(1.48 - backLowest, 0.02, 0.005);
}

TEST(TShirt, BackLayoutIsSeenFromBehind) {
  // The wearer's left sleeve (x > 0) is on the right of the front layout and on the left of the back layout.
  const pg::Garment& g = shirt();
  for (int f = 0; f < g.mesh.numFaces(); ++f) {
    if (g.panels[g.facePanel[f]].rfind("left_sleeve", 0) != 0) continue;
    EXPECT_GT(g.mesh.V(g.mesh.F(f, 0), 0), 0);
    double u = g.mesh.UV(g.mesh.FUV(f, 0), 0);
    EXPECT_TRUE(g.faceLayout[f] == 0 ? u > 0 : u < 0);
  }
}

TEST(TShirt, IsDeterministic) {
  pg::Garment again = pg::makeTShirt();
  EXPECT_EQ(again.mesh.V, shirt().mesh.V);
  EXPECT_EQ(again.mesh.F, shirt().mesh.F);
  EXPECT_EQ(again.mesh.UV, shirt().mesh.UV);
  EXPECT_EQ(again.mesh.FUV, shirt().mesh.FUV);
  EXPECT_EQ(again.facePanel, shirt().facePanel);
  ASSERT_EQ(again.seams.size(), shirt().seams.size());
  for (size_t s = 0; s < again.seams.size(); ++s) EXPECT_EQ(again.seams[s].vertices, shirt().seams[s].vertices);
}

TEST(TShirt, OptionsRejectNonsense) {
  auto rejects = [](auto change) {
    pg::TShirtOptions options;
    change(options);
    EXPECT_THROW(options.validate(), pc::InputError);
    EXPECT_THROW(pg::makeTShirt(options), pc::InputError);
  };
  rejects([](pg::TShirtOptions& o) { o.length = -0.67; });
  rejects([](pg::TShirtOptions& o) { o.targetVertices = 99; });
  rejects([](pg::TShirtOptions& o) { o.halfWidth = std::nan(""); });
  rejects([](pg::TShirtOptions& o) { o.shoulderHalfWidth = 0.3; });  // wider than the body
  rejects([](pg::TShirtOptions& o) { o.armpitDepth = 0.7; });        // below the hem
  rejects([](pg::TShirtOptions& o) { o.sleeveLength = 0.05; });      // does not reach past the body
  rejects([](pg::TShirtOptions& o) { o.shoulderHalfWidth = 0.1; });  // armhole too slanted to mesh well
  EXPECT_NO_THROW(pg::TShirtOptions().validate());
  try {
    pg::TShirtOptions options;
    options.length = -1;
    options.validate();
  } catch (const pc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("length"), std::string::npos) << e.what();
  }
}

TEST(TShirt, OtherSizesStitchToo) {
  pg::TShirtOptions options;
  options.targetVertices = 800;
  options.length = 0.75;
  options.halfWidth = 0.3;
  options.frontNeckDepth = 0.12;
  pg::Garment g = pg::makeTShirt(options);
  expectWellFormed(g);
  expectBoundaryIsOpenings(g);
  EXPECT_NEAR(g.length(), 0.75, 1e-9);
  EXPECT_GE(minAngleDegrees(g), 20.0);
}

TEST(Necktie, ShapeAndMesh) {
  const pg::Garment& g = tie();
  std::cout << "[ necktie  ] " << g.summary() << "\n[ necktie  ] " << g.meshing.summary(g.mesh.numVertices())
            << std::endl;
  expectWellFormed(g);
  EXPECT_EQ(g.layouts, std::vector<std::string>{"tie"});
  EXPECT_TRUE(g.seams.empty());
  ASSERT_EQ(g.openings.size(), 1u);
  EXPECT_EQ(g.openings[0].name, "outline");
  expectBoundaryIsOpenings(g);
  EXPECT_NEAR(g.mesh.numVertices(), 500, 50);
  Eigen::Vector2d size = g.layoutBounds(0).sizes();
  double aspect = size.y() / size.x();
  EXPECT_GE(aspect, 3.5);
  EXPECT_LE(aspect, 5.0);
  EXPECT_NEAR(g.length(), 0.44, 1e-9);
  EXPECT_GE(minAngleDegrees(g), 20.0);
  // Hangs flat in front of the chest, top near 1.45 m, normals towards +z.
  EXPECT_NEAR(g.mesh.V.col(1).maxCoeff(), 1.45, 1e-9);
  EXPECT_TRUE((g.mesh.V.col(2).array() == 0.13).all());
  Eigen::MatrixX3d N = pc::faceNormals(g.mesh.V, g.mesh.F);
  EXPECT_GT(N.col(2).minCoeff(), 0.999);
}

TEST(Necktie, DeterministicAndValidated) {
  pg::Garment again = pg::makeNecktie();
  EXPECT_EQ(again.mesh.V, tie().mesh.V);
  EXPECT_EQ(again.mesh.F, tie().mesh.F);
  EXPECT_EQ(again.mesh.UV, tie().mesh.UV);
  pg::NecktieOptions bad;
  bad.length = -0.44;
  EXPECT_THROW(pg::makeNecktie(bad), pc::InputError);
  bad = {};
  bad.targetVertices = 10;
  EXPECT_THROW(bad.validate(), pc::InputError);
  bad = {};
  bad.bladeWidth = 0.03;  // narrower than the knot
  EXPECT_THROW(bad.validate(), pc::InputError);
  bad = {};
  bad.tipHeight = 0.2;  // a needle tip
  EXPECT_THROW(bad.validate(), pc::InputError);
}

TEST(Garment, QueriesRejectUnknownLayouts) {
  EXPECT_EQ(shirt().layoutIndex("back"), 1);
  EXPECT_THROW(shirt().layoutIndex("side"), pc::InputError);
  EXPECT_THROW(shirt().layoutBounds(2), pc::InputError);
  EXPECT_EQ(shirt().findSeam("nope"), nullptr);
}

TEST(TShirt, SeamsSplitByTheMesherAreMatchedAcrossLayouts) {
  // Sparse first samples: the mesher splits boundary edges, differently in the two layouts (their necklines differ),
  // and the seam matching needs several rounds.
  pg::TShirtOptions options;
  options.boundarySpacing = 2.0;
  pg::Garment g = pg::makeTShirt(options);
  std::cout << "[ tshirt   ] sparse seams: " << g.meshing.summary(g.mesh.numVertices()) << std::endl;
  EXPECT_GE(g.meshing.stitchRounds, 2);
  expectWellFormed(g);
  expectBoundaryIsOpenings(g);
  EXPECT_GE(minAngleDegrees(g), 20.0);
  auto front = layoutEdges(g, 0), back = layoutEdges(g, 1);
  for (const auto& seam : g.seams) {
    if (!seam.joinsLayouts) continue;
    for (size_t i = 0; i + 1 < seam.vertices.size(); ++i) {
      auto e = edgeKey(seam.vertices[i], seam.vertices[i + 1]);
      EXPECT_TRUE(front.count(e) && back.count(e)) << seam.name << ": edge " << i;
    }
    EXPECT_NEAR(uvLength(g, seam.vertices, 0), uvLength(g, seam.vertices, 1), 1e-9) << seam.name;
  }
}

TEST(TShirt, CageLinesRunAlongMeshEdgesWhereTheyBelong) {
  const pg::Garment& g = shirt();
  const pg::TShirtOptions o;
  auto front = layoutEdges(g, 0), back = layoutEdges(g, 1);
  ASSERT_EQ(g.lines.size(), 10u);
  for (const auto& line : g.lines) {
    const size_t n = line.vertices.size();
    ASSERT_GE(n, 3u) << line.name;
    EXPECT_EQ(line.closed, line.kind == pg::CurveKind::Loop) << line.name;
    std::set<int> seen(line.vertices.begin(), line.vertices.end());
    EXPECT_EQ(seen.size(), n) << line.name << " repeats a vertex";
    for (size_t i = 0; i + (line.closed ? 0 : 1) < n; ++i) {
      auto e = edgeKey(line.vertices[i], line.vertices[(i + 1) % n]);
      EXPECT_TRUE(front.count(e) || back.count(e)) << line.name << ": step " << i << " is no mesh edge";
    }
  }
  // Pattern-space positions: garment x (UV u on the front, -u on the back) and y above the hem.
  auto xy = [&](int v) {
    const int l = g.vertexUV(v, 0) >= 0 ? 0 : 1;
    Eigen::Vector2d uv = g.mesh.UV.row(g.vertexUV(v, l));
    return Eigen::Vector2d(l == 0 ? uv.x() : -uv.x(), uv.y());
  };
  for (int v : g.findLine("chest")->vertices) EXPECT_NEAR(xy(v).y(), o.chestHeight, 1e-12);
  for (int v : g.findLine("waist")->vertices) EXPECT_NEAR(xy(v).y(), o.waistHeight, 1e-12);
  for (const char* name : {"centre_front", "centre_back"}) {
    const auto& chain = g.findLine(name)->vertices;
    for (int v : chain) EXPECT_NEAR(xy(v).x(), 0.0, 1e-12) << name;
    EXPECT_NEAR(xy(chain.back()).y(), 0.0, 1e-12) << name;
  }
  for (int v : g.findLine("side_panel_back_left")->vertices) EXPECT_NEAR(xy(v).x(), o.sidePanelX, 1e-12);
  for (int v : g.findLine("side_panel_front_right")->vertices) EXPECT_NEAR(xy(v).x(), -o.sidePanelX, 1e-12);
  // The chest loop meets each side seam once, at the same vertex on both layouts, at the same height.
  for (const char* side : {"side_left", "side_right"}) {
    const auto& seam = g.findSeam(side)->vertices;
    int met = 0;
    for (int v : g.findLine("chest")->vertices) {
      if (std::find(seam.begin(), seam.end(), v) == seam.end()) continue;
      ++met;
      EXPECT_NEAR(g.mesh.UV(g.vertexUV(v, 0), 1), o.chestHeight, 1e-12);
      EXPECT_NEAR(g.mesh.UV(g.vertexUV(v, 1), 1), o.chestHeight, 1e-12);
    }
    EXPECT_EQ(met, 1) << side;
  }
}

TEST(Necktie, BandLinesCrossTheBlade) {
  const pg::Garment g = pg::makeNecktie();
  ASSERT_EQ(g.lines.size(), 4u);
  for (size_t b = 0; b < g.lines.size(); ++b) {
    EXPECT_EQ(g.lines[b].name, "tie_band_" + std::to_string(b + 1));
    for (int v : g.lines[b].vertices) EXPECT_NEAR(g.mesh.UV(g.vertexUV(v, 0), 1), 0.44 * (b + 1) / 5, 1e-12);
  }
  pg::NecktieOptions tooMany;
  tooMany.bands = 10;  // lowest line at 0.044, below the tip's 0.06
  EXPECT_THROW(tooMany.validate(), pc::InputError);
}
