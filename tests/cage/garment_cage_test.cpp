// The garment cage: seams, openings and cage lines of the templates as one validated curve network.
#include "pixelcloth/cage/garment_cage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "support/cage_fixtures.h"

namespace pcg = pixelcloth::cage;
namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;

namespace {
const pixelcloth::garment::Garment& shirt() { return pixelcloth::testing::tshirt(); }
const pcg::Cage& shirtCage() { return pixelcloth::testing::tshirtCage(); }

std::set<std::pair<int, int>> meshEdges(const Eigen::MatrixX3i& F) {
  std::set<std::pair<int, int>> edges;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) edges.insert(std::minmax(F(f, k), F(f, (k + 1) % 3)));
  return edges;
}

/// Layouts that have the mesh edge (a, b) as an edge of one of their faces.
std::set<int> layoutsOfEdge(const pg::Garment& g, int a, int b) {
  std::set<int> layouts;
  for (int f = 0; f < g.mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (std::minmax(g.mesh.F(f, k), g.mesh.F(f, (k + 1) % 3)) == std::minmax(a, b)) layouts.insert(g.faceLayout[f]);
  return layouts;
}
}  // namespace

TEST(GarmentCage, TShirtHasEveryNamedCurveWithItsKind) {
  const pcg::Cage& cage = shirtCage();
  const std::map<std::string, pcg::CurveKind> expected = {{"side_left", pcg::CurveKind::Seam},
                                                          {"side_right", pcg::CurveKind::Seam},
                                                          {"underarm_left", pcg::CurveKind::Seam},
                                                          {"underarm_right", pcg::CurveKind::Seam},
                                                          {"shoulder_left", pcg::CurveKind::Seam},
                                                          {"shoulder_right", pcg::CurveKind::Seam},
                                                          {"sleeve_top_left", pcg::CurveKind::Seam},
                                                          {"sleeve_top_right", pcg::CurveKind::Seam},
                                                          {"armhole_front_left", pcg::CurveKind::Seam},
                                                          {"armhole_front_right", pcg::CurveKind::Seam},
                                                          {"armhole_back_left", pcg::CurveKind::Seam},
                                                          {"armhole_back_right", pcg::CurveKind::Seam},
                                                          {"hem", pcg::CurveKind::Opening},
                                                          {"neckline", pcg::CurveKind::Opening},
                                                          {"sleeve_hem_left", pcg::CurveKind::Opening},
                                                          {"sleeve_hem_right", pcg::CurveKind::Opening},
                                                          {"chest", pcg::CurveKind::Loop},
                                                          {"waist", pcg::CurveKind::Loop},
                                                          {"bicep_left", pcg::CurveKind::Loop},
                                                          {"bicep_right", pcg::CurveKind::Loop},
                                                          {"centre_front", pcg::CurveKind::CentreLine},
                                                          {"centre_back", pcg::CurveKind::CentreLine},
                                                          {"side_panel_front_left", pcg::CurveKind::Split},
                                                          {"side_panel_front_right", pcg::CurveKind::Split},
                                                          {"side_panel_back_left", pcg::CurveKind::Split},
                                                          {"side_panel_back_right", pcg::CurveKind::Split}};
  EXPECT_EQ(cage.curves.size(), expected.size());
  for (const auto& [name, kind] : expected) {
    const pcg::CageCurve* curve = cage.findCurve(name);
    ASSERT_NE(curve, nullptr) << name;
    EXPECT_EQ(curve->kind, kind) << name;
    EXPECT_EQ(curve->closed, kind == pcg::CurveKind::Loop || kind == pcg::CurveKind::Opening) << name;
  }
}

TEST(GarmentCage, CurvesRunAlongMeshEdgesAndValidate) {
  const pcg::Cage& cage = shirtCage();
  EXPECT_NO_THROW(cage.validate(shirt().mesh.F, shirt().mesh.numVertices()));
  const auto edges = meshEdges(shirt().mesh.F);
  for (const auto& edge : pcg::cutEdges(cage)) EXPECT_TRUE(edges.count(edge)) << edge.first << "-" << edge.second;
  EXPECT_EQ(pcg::cutEdges(cage), cage.edges());
}

TEST(GarmentCage, LoopsCloseThroughBothLayouts) {
  const pg::Garment& g = shirt();
  for (const char* name : {"chest", "waist", "bicep_left", "bicep_right"}) {
    const pcg::CageCurve* loop = shirtCage().findCurve(name);
    ASSERT_NE(loop, nullptr);
    ASSERT_TRUE(loop->closed);
    // Every edge lies in one layout; the loop uses both, and crosses between them exactly twice, at stitched seam
    // vertices (which have a UV in both layouts).
    std::set<int> visited;
    int crossings = 0;
    const size_t n = loop->vertices.size();
    for (size_t i = 0; i < n; ++i) {
      const int a = loop->vertices[i], b = loop->vertices[(i + 1) % n], c = loop->vertices[(i + 2) % n];
      const std::set<int> here = layoutsOfEdge(g, a, b), next = layoutsOfEdge(g, b, c);
      ASSERT_EQ(here.size(), 1u) << name << " edge " << a << "-" << b;
      visited.insert(*here.begin());
      if (here != next) {
        ++crossings;
        EXPECT_GE(g.vertexUV(b, 0), 0) << name;
        EXPECT_GE(g.vertexUV(b, 1), 0) << name;
      }
    }
    EXPECT_EQ(visited, (std::set<int>{0, 1})) << name;
    EXPECT_EQ(crossings, 2) << name;
  }
}

TEST(GarmentCage, LoopsMeetTheSeamsTheyCross) {
  auto shared = [&](const std::string& a, const std::string& b) {
    const pcg::CageCurve *ca = shirtCage().findCurve(a), *cb = shirtCage().findCurve(b);
    int count = 0;
    for (int v : ca->vertices) count += std::count(cb->vertices.begin(), cb->vertices.end(), v) > 0;
    return count;
  };
  for (const char* side : {"left", "right"}) {
    EXPECT_EQ(shared("chest", std::string("side_") + side), 1);
    EXPECT_EQ(shared("waist", std::string("side_") + side), 1);
    EXPECT_EQ(shared(std::string("bicep_") + side, std::string("underarm_") + side), 1);
    EXPECT_EQ(shared(std::string("bicep_") + side, std::string("sleeve_top_") + side), 1);
  }
  EXPECT_EQ(shared("centre_front", "neckline"), 1);
  EXPECT_EQ(shared("centre_front", "hem"), 1);
  EXPECT_EQ(shared("centre_front", "chest"), 1);
  EXPECT_EQ(shared("centre_back", "waist"), 1);
  EXPECT_EQ(shared("side_panel_front_left", "waist"), 1);
  EXPECT_EQ(shared("side_panel_back_right", "chest"), 1);
}

TEST(GarmentCage, NodesAreTheJunctions) {
  const pcg::Cage& cage = shirtCage();
  // Per layout: 8 ends of the centre line and the side panels (on neckline, hem, chest); chest and waist crossing
  // centre line and side panels (6); per sleeve half 4 seam corners at shoulder/armpit ... counted loosely: the cage
  // is a connected graph of a few dozen junctions, not one per vertex.
  EXPECT_GE(cage.nodes.size(), 30u);
  EXPECT_LE(cage.nodes.size(), 60u);
  std::set<int> vertices;
  for (const auto& node : cage.nodes) EXPECT_TRUE(vertices.insert(node.vertex).second) << node.name;
  EXPECT_GE(cage.findNode("chest/side_left"), 0);
  EXPECT_GE(cage.findNode("centre_front/chest"), 0);
}

TEST(GarmentCage, Necktie) {
  const pg::Garment tie = pg::makeNecktie();
  const pcg::Cage cage = pcg::garmentCage(tie);
  ASSERT_NE(cage.findCurve("outline"), nullptr);
  EXPECT_EQ(cage.findCurve("outline")->kind, pcg::CurveKind::Opening);
  for (const char* name : {"tie_band_1", "tie_band_2", "tie_band_3", "tie_band_4"}) {
    const pcg::CageCurve* band = cage.findCurve(name);
    ASSERT_NE(band, nullptr) << name;
    EXPECT_EQ(band->kind, pcg::CurveKind::Split);
    // Both ends on the outline.
    const auto& outline = cage.findCurve("outline")->vertices;
    for (int end : {band->vertices.front(), band->vertices.back()})
      EXPECT_NE(std::find(outline.begin(), outline.end(), end), outline.end()) << name;
  }
  EXPECT_NO_THROW(cage.validate(tie.mesh.F, tie.mesh.numVertices()));
}
