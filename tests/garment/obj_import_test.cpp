// Garment OBJ import without a cage file, and the exporter that writes our templates the way users' programs do:
// round trips keep seams, openings, layouts and panels (compared by 3D position, since the file's vertex order is not
// ours); fixes are noted; files that cannot be fixed are refused naming the file and what was expected.
#include "pixelcloth/garment/obj_import.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/garment/garment.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
namespace pg = pixelcloth::garment;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

namespace {

const pg::Garment& shirt() { return pixelcloth::testing::tshirt(); }

const pg::Garment& necktie() {
  static const pg::Garment tie = pg::makeNecktie();
  return tie;
}

/// Each vertex of `imported` as the vertex of `original` at the same 3D position (within 1e-5 m); fails the test for
/// a vertex with no match.
std::vector<int> matchVertices(const pg::Garment& original, const pg::Garment& imported) {
  constexpr double kCell = 1e-3, kTolerance = 1e-5;
  auto cellOf = [&](const Eigen::Vector3d& p, int dx, int dy, int dz) {
    const long x = std::lround(std::floor(p.x() / kCell)) + dx, y = std::lround(std::floor(p.y() / kCell)) + dy,
               z = std::lround(std::floor(p.z() / kCell)) + dz;
    return std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(z);
  };
  std::unordered_map<std::string, std::vector<int>> grid;
  for (int v = 0; v < original.mesh.numVertices(); ++v)
    grid[cellOf(original.mesh.V.row(v).transpose(), 0, 0, 0)].push_back(v);
  std::vector<int> match(imported.mesh.numVertices(), -1);
  for (int v = 0; v < imported.mesh.numVertices(); ++v) {
    const Eigen::Vector3d p = imported.mesh.V.row(v).transpose();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = grid.find(cellOf(p, dx, dy, dz));
          if (it == grid.end()) continue;
          for (int w : it->second)
            if ((original.mesh.V.row(w).transpose() - p).norm() < kTolerance) match[v] = w;
        }
    EXPECT_GE(match[v], 0) << "imported vertex " << v << " at " << p.transpose() << " has no original";
  }
  return match;
}

/// Seams (or openings) by name, each as the set of original vertices.
template <typename Curve>
std::map<std::string, std::set<int>> curveSets(const std::vector<Curve>& curves, const std::vector<int>& match) {
  std::map<std::string, std::set<int>> sets;
  for (const Curve& curve : curves) {
    std::set<int>& set = sets[curve.name];
    for (int v : curve.vertices) set.insert(match.empty() ? v : match[v]);
  }
  return sets;
}

std::set<std::string> names(const std::vector<std::string>& list) { return {list.begin(), list.end()}; }

/// Same seams (names, vertex sets, joinsLayouts), openings (names, vertex sets), layouts and panels (names, and the
/// layout and panel of every face), as the original; each layout's UVs the original's up to a shift.
void expectSameGarment(const pg::Garment& original, const pg::Garment& imported, const std::vector<int>& match) {
  EXPECT_EQ(curveSets(imported.seams, match), curveSets(original.seams, {}));
  EXPECT_EQ(curveSets(imported.openings, match), curveSets(original.openings, {}));
  for (const pg::Seam& seam : imported.seams) {
    const pg::Seam* before = original.findSeam(seam.name);
    ASSERT_NE(before, nullptr) << seam.name;
    EXPECT_EQ(seam.joinsLayouts, before->joinsLayouts) << seam.name;
  }
  EXPECT_EQ(names(imported.layouts), names(original.layouts));
  EXPECT_EQ(names(imported.panels), names(original.panels));
  std::map<std::set<int>, int> originalFace;
  for (int f = 0; f < original.mesh.numFaces(); ++f)
    originalFace[{original.mesh.F(f, 0), original.mesh.F(f, 1), original.mesh.F(f, 2)}] = f;
  ASSERT_EQ(imported.mesh.numFaces(), original.mesh.numFaces());
  std::map<int, Eigen::Vector2d> shift;  // imported layout -> UV shift from the original
  for (int f = 0; f < imported.mesh.numFaces(); ++f) {
    auto it =
        originalFace.find({match[imported.mesh.F(f, 0)], match[imported.mesh.F(f, 1)], match[imported.mesh.F(f, 2)]});
    ASSERT_NE(it, originalFace.end()) << "imported face " << f + 1 << " is no face of the original";
    const int g = it->second;
    ASSERT_EQ(imported.layouts[imported.faceLayout[f]], original.layouts[original.faceLayout[g]]) << "face " << f + 1;
    ASSERT_EQ(imported.panels[imported.facePanel[f]], original.panels[original.facePanel[g]]) << "face " << f + 1;
    for (int k = 0; k < 3; ++k) {
      const int v = imported.mesh.F(f, k);
      int j = 0;
      while (original.mesh.F(g, j) != match[v]) ++j;
      const Eigen::Vector2d delta =
          imported.mesh.UV.row(imported.mesh.FUV(f, k)) - original.mesh.UV.row(original.mesh.FUV(g, j));
      auto [known, inserted] = shift.emplace(imported.faceLayout[f], delta);
      ASSERT_LT((known->second - delta).norm(), 1e-6) << "face " << f + 1 << ": UVs are not the original's shifted";
    }
  }
}

/// Exports `garment`, imports it back; the report's notes in `report`.
pg::Garment roundTrip(const pg::Garment& garment, const fs::path& file, const pg::ObjExportOptions& exportOptions,
                      const pg::ObjImportOptions& importOptions = {}, pg::ObjImportReport* report = nullptr) {
  pg::exportGarmentObj(garment, file, exportOptions);
  return pg::importGarmentObj(file, importOptions, report);
}

/// Every corner's UV is its vertex's one UV in the face's layout.
void expectOneUvPerVertexAndLayout(const pg::Garment& garment) {
  for (int f = 0; f < garment.mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(garment.mesh.FUV(f, k), garment.vertexUV(garment.mesh.F(f, k), garment.faceLayout[f]));
}

/// Total 3D and UV area of the faces of each layout.
void layoutAreas(const pg::Garment& garment, std::vector<double>& area3, std::vector<double>& areaUV) {
  area3.assign(garment.numLayouts(), 0.0);
  areaUV.assign(garment.numLayouts(), 0.0);
  const auto& m = garment.mesh;
  for (int f = 0; f < m.numFaces(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const Eigen::Vector2d p = m.UV.row(m.FUV(f, 0)), q = m.UV.row(m.FUV(f, 1)), r = m.UV.row(m.FUV(f, 2));
    area3[garment.faceLayout[f]] += 0.5 * (b - a).cross(c - a).norm();
    areaUV[garment.faceLayout[f]] += 0.5 * std::abs((q - p).x() * (r - p).y() - (q - p).y() * (r - p).x());
  }
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

// ---------------------------------------------------------------------------------------------------------------------
// Round trips

TEST(ObjImport, TShirtWithGroupsRoundTripsWithoutACage) {
  const fs::path file = freshDir("obj") / "shirt.obj";
  pg::ObjExportOptions options;
  options.groups = true;
  pg::ObjImportReport report;
  const pg::Garment imported = roundTrip(shirt(), file, options, {}, &report);
  EXPECT_EQ(imported.name, "shirt");
  EXPECT_EQ(imported.numLayouts(), 2);
  EXPECT_EQ(imported.panels.size(), 6u);
  EXPECT_TRUE(report.notes.empty()) << report.summary();
  expectSameGarment(shirt(), imported, matchVertices(shirt(), imported));
  // Armholes are sewn inside a layout; every other seam joins the front and the back.
  EXPECT_FALSE(imported.findSeam("armhole_front_left")->joinsLayouts);
  EXPECT_TRUE(imported.findSeam("side_left")->joinsLayouts);
}

TEST(ObjImport, ShuffledVertexOrderImportsTheSameGarment) {
  const fs::path file = freshDir("obj") / "shuffled.obj";
  pg::ObjExportOptions options;
  options.groups = true;
  options.shuffleSeed = 12345;
  const pg::Garment imported = roundTrip(shirt(), file, options);
  const std::vector<int> match = matchVertices(shirt(), imported);
  int moved = 0;
  for (size_t v = 0; v < match.size(); ++v) moved += match[v] != static_cast<int>(v);
  EXPECT_GT(moved, static_cast<int>(match.size()) / 2);
  expectSameGarment(shirt(), imported, match);
}

TEST(ObjImport, MovedTurnedAndScaledFileImportsWithTheMatchingOptions) {
  const fs::path dir = freshDir("obj");
  pg::ObjExportOptions exportOptions;
  exportOptions.groups = true;
  exportOptions.shuffleSeed = 7;
  exportOptions.up = 'z';
  exportOptions.scale = 0.01;  // the file is in centimetres
  exportOptions.translate = Eigen::Vector3d(0.3, -0.2, 1.0);
  pg::ObjImportOptions importOptions;
  importOptions.up = 'z';
  importOptions.scale = 0.01;
  importOptions.translate = exportOptions.translate;
  importOptions.name = "moved_shirt";
  const pg::Garment imported = roundTrip(shirt(), dir / "moved.obj", exportOptions, importOptions);
  EXPECT_EQ(imported.name, "moved_shirt");
  expectSameGarment(shirt(), imported, matchVertices(shirt(), imported));
  // The file itself is Z up and in centimetres.
  const pixelcloth::core::Mesh file = pixelcloth::core::readMesh(dir / "moved.obj");
  EXPECT_GT(file.V.col(2).maxCoeff() - file.V.col(2).minCoeff(), 50.0);
}

TEST(ObjImport, PlacementOptionsAlsoMoveAGarmentReadWithACage) {
  pg::Garment garment = shirt();
  pg::ObjImportOptions options;
  options.up = 'z';
  options.scale = 2;
  options.translate = Eigen::Vector3d(1, 2, 3);
  pg::placeGarment(garment, options);
  const Eigen::Vector3d before = shirt().mesh.V.row(10), after = garment.mesh.V.row(10);
  EXPECT_LT((after - (2 * Eigen::Vector3d(before.x(), before.z(), -before.y()) + options.translate)).norm(), 1e-12);
}

TEST(ObjImport, TubeSleevesAreCutAlongTheSleeveTop) {
  const fs::path file = freshDir("obj") / "tube.obj";
  pg::ObjExportOptions options;
  options.tubeSleeves = true;
  options.shuffleSeed = 99;
  pg::ObjImportReport report;
  const pg::Garment imported = roundTrip(shirt(), file, options, {}, &report);
  // The file holds each underarm vertex twice in its sleeve's island.
  const pixelcloth::core::Mesh raw = pixelcloth::core::readMesh(file);
  EXPECT_GT(raw.UV.rows(), shirt().mesh.UV.rows());

  expectOneUvPerVertexAndLayout(imported);
  const std::vector<int> match = matchVertices(shirt(), imported);
  const auto openings = curveSets(imported.openings, match);
  EXPECT_EQ(openings, curveSets(shirt().openings, {}));  // hem, neckline, sleeve_hem_left, sleeve_hem_right
  const auto seams = curveSets(imported.seams, match), expected = curveSets(shirt().seams, {});
  for (const char* name :
       {"side_left", "side_right", "underarm_left", "underarm_right", "shoulder_left", "shoulder_right",
        "armhole_front_left", "armhole_front_right", "armhole_back_left", "armhole_back_right"}) {
    ASSERT_TRUE(seams.count(name)) << name << " not found";
    EXPECT_EQ(seams.at(name), expected.at(name)) << name;
  }
  // Torso, two sleeve islands each cut in two: six layouts and panels; the armholes now join layouts.
  EXPECT_EQ(imported.numLayouts(), 6);
  EXPECT_EQ(imported.panels, shirt().panels);  // in the template's order
  EXPECT_EQ(imported.layouts[0], "front");     // the first layout gives the garment's length
  EXPECT_NEAR(imported.length(), shirt().length(), 1e-6);
  EXPECT_TRUE(imported.findSeam("armhole_front_left")->joinsLayouts);
  // The cut is the new sleeve-top seam, from the shoulder point to the sleeve hem.
  for (const std::string side : {"left", "right"}) {
    const pg::Seam* top = imported.findSeam("sleeve_top_" + side);
    ASSERT_NE(top, nullptr) << side;
    EXPECT_TRUE(top->joinsLayouts);
    const pg::Seam* original = shirt().findSeam("sleeve_top_" + side);
    EXPECT_EQ(match[top->vertices.front()], original->vertices.front()) << side;
    EXPECT_EQ(match[top->vertices.back()], original->vertices.back()) << side;
    // On this mesh the cut follows the template's sleeve top exactly.
    EXPECT_EQ(seams.at("sleeve_top_" + side), expected.at("sleeve_top_" + side)) << side;
  }
  ASSERT_EQ(report.notes.size(), 2u) << report.summary();
  EXPECT_TRUE(contains(report.notes[0], "cut in two")) << report.notes[0];
  EXPECT_TRUE(contains(report.summary(), "_sleeve)")) << report.summary();
}

TEST(ObjImport, SeparatePanelsBecomeLayoutsJoinedByArmholeSeams) {
  const fs::path file = freshDir("obj") / "pieces.obj";
  pg::ObjExportOptions options;
  options.separatePanels = true;
  const pg::Garment imported = roundTrip(shirt(), file, options);
  EXPECT_EQ(imported.numLayouts(), 6);
  const std::vector<int> match = matchVertices(shirt(), imported);
  EXPECT_EQ(curveSets(imported.seams, match), curveSets(shirt().seams, {}));
  EXPECT_EQ(names(imported.panels), names(shirt().panels));
}

TEST(ObjImport, WithoutGroupsTheIslandsAreThePanelsAndSeamsSplitAtTheArmpit) {
  const fs::path file = freshDir("obj") / "islands.obj";
  const pg::Garment imported = roundTrip(shirt(), file, {});
  EXPECT_EQ(names(imported.panels), (std::set<std::string>{"front", "back"}));
  const std::vector<int> match = matchVertices(shirt(), imported);
  const auto seams = curveSets(imported.seams, match), expected = curveSets(shirt().seams, {});
  // The side seam turns into the underarm at the armpit (a sharp corner of the outline): two seams.
  EXPECT_EQ(seams.at("side_left"), expected.at("side_left"));
  EXPECT_EQ(seams.at("underarm_right"), expected.at("underarm_right"));
  // The shoulder runs straight on into the sleeve top: one seam.
  std::set<int> shoulder = expected.at("shoulder_left");
  shoulder.insert(expected.at("sleeve_top_left").begin(), expected.at("sleeve_top_left").end());
  EXPECT_EQ(seams.at("shoulder_left"), shoulder);
}

TEST(ObjImport, NecktieRoundTripsAsOnePanelWithItsOutline) {
  const fs::path file = freshDir("obj") / "necktie.obj";
  pg::ObjExportOptions options;
  options.shuffleSeed = 5;
  const pg::Garment imported = roundTrip(necktie(), file, options);
  EXPECT_EQ(imported.numLayouts(), 1);
  EXPECT_EQ(imported.panels, std::vector<std::string>{"necktie"});
  EXPECT_TRUE(imported.seams.empty());
  const std::vector<int> match = matchVertices(necktie(), imported);
  EXPECT_EQ(curveSets(imported.openings, match), curveSets(necktie().openings, {}));  // "outline"
}

TEST(ObjImport, SkirtImportsWithHemWaistAndSideSeams) {
  // A flared tube of two panels, front (z > 0) and back, each its own UV island laid out flat (arc length across,
  // height up), sewn at x = +-r: no sleeves, no neckline.
  const fs::path file = freshDir("obj") / "skirt.obj";
  const int n = 16, m = 10;  // segments per half round, rows
  auto radius = [&](int j) { return 0.35 - 0.1 * j / m; };
  std::ostringstream out;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i < 2 * n; ++i) {
      const double angle = M_PI * i / n;
      out << "v " << radius(j) * std::cos(angle) << ' ' << 0.4 + 0.6 * j / m << ' ' << radius(j) * std::sin(angle)
          << '\n';
    }
  // vt of (panel, i, j), i from 0 to n along the panel: u = -arc length from the panel's start, v = height.
  for (int panel = 0; panel < 2; ++panel)
    for (int j = 0; j <= m; ++j)
      for (int i = 0; i <= n; ++i) out << "vt " << -radius(j) * M_PI * i / n << ' ' << 0.6 * j / m << '\n';
  auto v = [&](int i, int j) { return j * 2 * n + (i % (2 * n)) + 1; };
  auto vt = [&](int panel, int i, int j) { return panel * (m + 1) * (n + 1) + j * (n + 1) + i + 1; };
  for (int panel = 0; panel < 2; ++panel) {
    out << "g " << (panel == 0 ? "Skirt_Front" : "Skirt_Back") << '\n';
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = panel * n + i;
        out << "f " << v(a, j) << '/' << vt(panel, i, j) << ' ' << v(a, j + 1) << '/' << vt(panel, i, j + 1) << ' '
            << v(a + 1, j + 1) << '/' << vt(panel, i + 1, j + 1) << ' ' << v(a + 1, j) << '/' << vt(panel, i + 1, j)
            << '\n';
      }
  }
  pixelcloth::core::writeTextAtomically(file, out.str());
  pg::ObjImportReport report;
  const pg::Garment skirt = pg::importGarmentObj(file, {}, &report);
  EXPECT_TRUE(report.notes.empty()) << report.summary();
  EXPECT_EQ(skirt.panels, (std::vector<std::string>{"front", "back"}));
  EXPECT_EQ(skirt.layouts, (std::vector<std::string>{"front", "back"}));
  ASSERT_EQ(skirt.openings.size(), 2u);
  EXPECT_EQ(skirt.openings[0].name, "hem");
  EXPECT_EQ(skirt.openings[1].name, "waist");
  ASSERT_EQ(skirt.seams.size(), 2u);
  EXPECT_EQ(skirt.seams[0].name, "side_left");
  EXPECT_EQ(skirt.seams[1].name, "side_right");
  for (const pg::Seam& seam : skirt.seams) {
    EXPECT_EQ(seam.vertices.size(), static_cast<size_t>(m + 1));
    EXPECT_TRUE(seam.joinsLayouts);
    // From the waist down, on the wearer's left (+x) for side_left.
    EXPECT_GT(skirt.mesh.V(seam.vertices.front(), 1), skirt.mesh.V(seam.vertices.back(), 1));
    EXPECT_EQ(skirt.mesh.V(seam.vertices.front(), 0) > 0, seam.name == "side_left");
  }
}

// ---------------------------------------------------------------------------------------------------------------------
// Fixes

TEST(ObjImport, NormalisedUvsAreRescaledToTheirThreeDArea) {
  const fs::path file = freshDir("obj") / "atlas.obj";
  pg::ObjExportOptions options;
  options.groups = true;
  options.uvScale = 1.0 / 40;
  pg::ObjImportReport report;
  const pg::Garment imported = roundTrip(shirt(), file, options, {}, &report);
  std::vector<double> area3, areaUV;
  layoutAreas(imported, area3, areaUV);
  for (int l = 0; l < imported.numLayouts(); ++l) EXPECT_NEAR(areaUV[l] / area3[l], 1.0, 0.02) << imported.layouts[l];
  ASSERT_EQ(report.notes.size(), 2u) << report.summary();
  EXPECT_TRUE(contains(report.notes[0], "rescaled x4")) << report.notes[0];
  EXPECT_TRUE(contains(report.summary(), "island 1 (front)")) << report.summary();
  // Seams and openings do not depend on the UV scale.
  const std::vector<int> match = matchVertices(shirt(), imported);
  EXPECT_EQ(curveSets(imported.seams, match), curveSets(shirt().seams, {}));
}

TEST(ObjImport, TemplateUvsAreMetresOfClothAndKept) {
  // The rest placement stretches the pattern near the seams (3D area 26% above the UV area), yet the UVs are metres:
  // the scale test goes by the median edge, which the stretch leaves alone.
  const fs::path file = freshDir("obj") / "kept.obj";
  pg::ObjImportReport report;
  const pg::Garment imported = roundTrip(shirt(), file, {}, {}, &report);
  EXPECT_TRUE(report.notes.empty()) << report.summary();
  EXPECT_EQ(report.summary(), "no fixes");
}

TEST(ObjImport, ClockwiseUvsAreMirrored) {
  const fs::path dir = freshDir("obj");
  pg::exportGarmentObj(necktie(), dir / "tie.obj");
  // Negate every u: the whole island runs clockwise.
  std::string text = pixelcloth::core::readTextFile(dir / "tie.obj"), mirrored;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("vt ", 0) == 0) {
      std::istringstream words(line.substr(3));
      double u = 0, v = 0;
      words >> u >> v;
      line = "vt " + std::to_string(-u) + " " + std::to_string(v);
    }
    mirrored += line + "\n";
  }
  pixelcloth::core::writeTextAtomically(dir / "mirrored.obj", mirrored);
  pg::ObjImportReport report;
  const pg::Garment imported = pg::importGarmentObj(dir / "mirrored.obj", {}, &report);
  ASSERT_EQ(report.notes.size(), 1u) << report.summary();
  EXPECT_TRUE(contains(report.notes[0], "mirrored")) << report.notes[0];
  const auto& m = imported.mesh;
  for (int f = 0; f < m.numFaces(); ++f) {
    const Eigen::Vector2d p = m.UV.row(m.FUV(f, 0)), q = m.UV.row(m.FUV(f, 1)), r = m.UV.row(m.FUV(f, 2));
    ASSERT_GT((q - p).x() * (r - p).y() - (q - p).y() * (r - p).x(), 0) << "face " << f + 1;
  }
}

TEST(ObjImport, FacesPointingInwardsAreTurnedRound) {
  const fs::path dir = freshDir("obj");
  pg::Garment inside = shirt();
  inside.mesh.F.col(1).swap(inside.mesh.F.col(2));
  inside.mesh.FUV.col(1).swap(inside.mesh.FUV.col(2));
  pg::ObjExportOptions options;
  options.groups = true;
  pg::ObjImportReport report;
  const pg::Garment imported = roundTrip(inside, dir / "inside.obj", options, {}, &report);
  EXPECT_TRUE(contains(report.summary(), "turned round")) << report.summary();
  const std::vector<int> match = matchVertices(shirt(), imported);
  EXPECT_EQ(curveSets(imported.seams, match), curveSets(shirt().seams, {}));
  // Openings run with the cloth on their left again: the same loops as the template's, in the same direction.
  for (const pg::Opening& opening : imported.openings) {
    const pg::Opening* before = nullptr;
    for (const pg::Opening& o : shirt().openings)
      if (o.name == opening.name) before = &o;
    ASSERT_NE(before, nullptr) << opening.name;
    const int a = match[opening.vertices[0]], b = match[opening.vertices[1]];
    const auto it = std::find(before->vertices.begin(), before->vertices.end(), a);
    ASSERT_NE(it, before->vertices.end());
    EXPECT_EQ(std::next(it) == before->vertices.end() ? before->vertices.front() : *std::next(it), b) << opening.name;
  }
}

// ---------------------------------------------------------------------------------------------------------------------
// Refusals: each names the file and what was expected

TEST(ObjImport, GarmentInCentimetresIsRefusedWithTheScaleThatFixesIt) {
  const fs::path file = freshDir("obj") / "centimetres.obj";
  pg::ObjExportOptions options;
  options.scale = 0.01;
  pg::exportGarmentObj(shirt(), file, options);
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "67 m tall")) << message;
  EXPECT_TRUE(contains(message, "expected 0.05 to 3 m")) << message;
  EXPECT_TRUE(contains(message, "centimetres? use --scale 0.01")) << message;
}

TEST(ObjImport, TinyGarmentIsRefusedWithAScaleThatFixesIt) {
  const fs::path file = freshDir("obj") / "tiny.obj";
  pg::ObjExportOptions options;
  options.scale = 100;
  pg::exportGarmentObj(shirt(), file, options);
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "0.0067 m tall")) << message;
  EXPECT_TRUE(contains(message, "use --scale")) << message;
}

TEST(ObjImport, ZUpGarmentReadAsYUpIsRefusedNamingUpZ) {
  const fs::path file = freshDir("obj") / "zup.obj";
  pg::ObjExportOptions options;
  options.up = 'z';
  pg::exportGarmentObj(shirt(), file, options);
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "lies along z")) << message;
  EXPECT_TRUE(contains(message, "expected Y up")) << message;
  EXPECT_TRUE(contains(message, "use --up z")) << message;
  pg::ObjImportOptions up;
  up.up = 'z';
  EXPECT_NO_THROW(pg::importGarmentObj(file, up));
  // And the other way round: a Y-up file read as Z up.
  pg::exportGarmentObj(shirt(), file);
  const std::string turned = inputErrorOf([&] { pg::importGarmentObj(file, up); });
  EXPECT_TRUE(contains(turned, "use --up y")) << turned;
}

namespace {

/// A 3 x 3 grid of vertices 10 cm apart standing in the plane z = 0 (y up), as 4 quads, with UVs equal to (x, y - 1)
/// except that the centre vertex's UV is `centreUv`.
std::string gridObj(const Eigen::Vector2d& centreUv) {
  std::ostringstream out;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) out << "v " << 0.1 * i << ' ' << 1 + 0.1 * j << " 0\n";
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d uv = i == 1 && j == 1 ? centreUv : Eigen::Vector2d(0.1 * i, 0.1 * j);
      out << "vt " << uv.x() << ' ' << uv.y() << '\n';
    }
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 3 * j + i + 1, b = a + 1, c = a + 4, d = a + 3;
      out << "f " << a << '/' << a << ' ' << b << '/' << b << ' ' << c << '/' << c << ' ' << d << '/' << d << '\n';
    }
  return out.str();
}

}  // namespace

TEST(ObjImport, SquareOfQuadsImportsAsOnePanel) {
  const fs::path file = freshDir("obj") / "square.obj";
  pixelcloth::core::writeTextAtomically(file, gridObj(Eigen::Vector2d(0.1, 0.1)));
  const pg::Garment square = pg::importGarmentObj(file);
  EXPECT_EQ(square.mesh.numFaces(), 8);
  EXPECT_EQ(square.openings.size(), 1u);
  EXPECT_EQ(square.openings[0].vertices.size(), 8u);
}

TEST(ObjImport, FoldedIslandIsRefusedNamingTheIslandAndAFace) {
  const fs::path file = freshDir("obj") / "folded.obj";
  // The centre vertex's UV lies outside the square: the triangles around it turn over.
  pixelcloth::core::writeTextAtomically(file, gridObj(Eigen::Vector2d(0.35, 0.1)));
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "island 1")) << message;
  EXPECT_TRUE(contains(message, "is folded in UV: face ")) << message;
  EXPECT_TRUE(contains(message, "expected a flat pattern piece")) << message;
}

TEST(ObjImport, OverlappingIslandIsRefusedNamingTheIslandAndItsFaces) {
  // A strip winding 400 degrees round a spiral in UV (a helix in 3D): every triangle counter-clockwise, but the
  // strip's second turn lies over its first.
  const fs::path file = freshDir("obj") / "spiral.obj";
  std::ostringstream out;
  const int n = 80;
  const double turn = 400.0 / 360 * 2 * M_PI;
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i <= n; ++i) {
      const double angle = turn * i / n;
      for (int r = 0; r < 2; ++r) {
        const double radius = 0.1 + 0.03 * r + 0.02 * angle / (2 * M_PI);
        const double x = radius * std::cos(angle), y = radius * std::sin(angle);
        if (pass == 0) out << "v " << x << ' ' << 1 + 0.4 * i / n << ' ' << y << '\n';
        if (pass == 1) out << "vt " << x << ' ' << y << '\n';
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i + 1, b = a + 1, c = a + 3, d = a + 2;
    out << "f " << a << '/' << a << ' ' << b << '/' << b << ' ' << c << '/' << c << ' ' << d << '/' << d << '\n';
  }
  pixelcloth::core::writeTextAtomically(file, out.str());
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "island 1")) << message;
  EXPECT_TRUE(contains(message, "overlaps itself in UV")) << message;
  EXPECT_TRUE(contains(message, "at faces ")) << message;
  EXPECT_TRUE(contains(message, "expected a flat pattern piece whose UVs do not overlap")) << message;
}

TEST(ObjImport, UnweldedSeamIsRefused) {
  // Two pattern pieces side by side, each with its own copy of the vertices along the edge they share.
  const fs::path file = freshDir("obj") / "unwelded.obj";
  pixelcloth::core::writeTextAtomically(file,
                                        "v 0 1 0\nv 0.1 1 0\nv 0.1 1.1 0\nv 0 1.1 0\n"
                                        "v 0.1 1 0\nv 0.2 1 0\nv 0.2 1.1 0\nv 0.1 1.1 0\n"
                                        "vt 0 0\nvt 0.1 0\nvt 0.1 0.1\nvt 0 0.1\n"
                                        "f 1/1 2/2 3/3 4/4\nf 5/1 6/2 7/3 8/4\n");
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "not sewn")) << message;
  EXPECT_TRUE(contains(message, "expected seams welded")) << message;
}

TEST(ObjImport, ObjWithoutUvsIsRefused) {
  const fs::path file = freshDir("obj") / "bare.obj";
  pixelcloth::core::writeTextAtomically(file, "v 0 1 0\nv 0.1 1 0\nv 0 1.1 0\nf 1 2 3\n");
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "no texture coordinates")) << message;
  EXPECT_TRUE(contains(message, "expected every face as 'f v/vt ...'")) << message;
}

TEST(ObjImport, MalformedGroupLineIsRefusedWithItsLine) {
  const fs::path file = freshDir("obj") / "material.obj";
  pixelcloth::core::writeTextAtomically(file,
                                        "v 0 1 0\nv 0.1 1 0\nv 0 1.1 0\nvt 0 0\nvt 0.1 0\nvt 0 0.1\nusemtl\n"
                                        "f 1/1 2/2 3/3\n");
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "(line 7)")) << message;
  EXPECT_TRUE(contains(message, "expected 'usemtl NAME'")) << message;
}

TEST(ObjImport, MalformedFaceIsRefusedWithItsLine) {
  const fs::path file = freshDir("obj") / "face.obj";
  pixelcloth::core::writeTextAtomically(file, "v 0 1 0\nv 0.1 1 0\nv 0 1.1 0\nvt 0 0\nvt 0.1 0\nf 1/1 2/2 3/3\n");
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "texture coordinate 3")) << message;
  EXPECT_TRUE(contains(message, "line 6")) << message;
}

TEST(ObjImport, UnusedVertexIsRefused) {
  const fs::path file = freshDir("obj") / "unused.obj";
  pixelcloth::core::writeTextAtomically(file,
                                        "v 0 1 0\nv 0.1 1 0\nv 0 1.1 0\nv 5 5 5\nvt 0 0\nvt 0.1 0\nvt 0 0.1\n"
                                        "f 1/1 2/2 3/3\n");
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "vertex 4 is used by no face")) << message;
  EXPECT_TRUE(contains(message, "expected every vertex on the garment surface")) << message;
}

TEST(ObjImport, OpeningsTouchingAtAVertexAreRefused) {
  // Two triangles meeting at vertex 3 only: the boundary passes through it twice.
  const fs::path file = freshDir("obj") / "bowtie.obj";
  pixelcloth::core::writeTextAtomically(file,
                                        "v 0 1 0\nv 0.1 1 0\nv 0.05 1.05 0\nv 0 1.1 0\nv 0.1 1.1 0\n"
                                        "vt 0 0\nvt 0.1 0\nvt 0.05 0.05\nvt 0 0.1\nvt 0.1 0.1\n"
                                        "f 1/1 2/2 3/3\nf 3/3 5/5 4/4\n");
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "vertex 3 lies on two stretches of the garment's boundary")) << message;
  EXPECT_TRUE(contains(message, "expected openings that meet at no vertex")) << message;
}

TEST(ObjImport, MissingFileIsRefused) {
  const fs::path file = freshDir("obj") / "missing.obj";
  const std::string message = inputErrorOf([&] { pg::importGarmentObj(file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "no such file; expected a garment OBJ")) << message;
  const std::string folder = inputErrorOf([&] { pg::importGarmentObj(file.parent_path()); });
  EXPECT_TRUE(contains(folder, file.parent_path().string())) << folder;
  EXPECT_TRUE(contains(folder, "not a regular file; expected a garment OBJ")) << folder;
}

TEST(ObjImport, OptionsOutOfRangeAreRefusedByName) {
  pg::ObjImportOptions options;
  options.up = 'x';
  EXPECT_TRUE(contains(inputErrorOf([&] { options.validate(); }), "up must be 'y' or 'z'"));
  options = {};
  options.scale = 0;
  EXPECT_TRUE(contains(inputErrorOf([&] { options.validate(); }), "scale must be a positive number"));
  options = {};
  options.translate.x() = NAN;
  EXPECT_TRUE(contains(inputErrorOf([&] { options.validate(); }), "translate must be finite"));
  pg::ObjExportOptions exportOptions;
  exportOptions.uvScale = -1;
  EXPECT_TRUE(contains(inputErrorOf([&] { exportOptions.validate(); }), "uvScale must be a positive number"));
}

TEST(ObjImport, TubeSleevesNeedTheShirtsSleeves) {
  const fs::path file = freshDir("obj") / "tie.obj";
  pg::ObjExportOptions options;
  options.tubeSleeves = true;
  const std::string message = inputErrorOf([&] { pg::exportGarmentObj(necktie(), file, options); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_TRUE(contains(message, "left_sleeve_front")) << message;
  EXPECT_FALSE(fs::exists(file));
}
