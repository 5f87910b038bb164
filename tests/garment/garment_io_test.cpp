// Garment folders: what saveGarment writes, and garment import (OBJ with UVs plus the cage's polylines).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/garment/garment.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

TEST(GarmentFolder, ObjKeepsUvsAndJsonDescribesSeams) {
  fs::path dir = freshDir("garment");
  const pg::Garment& shirt = pixelcloth::testing::tshirt();
  pg::saveGarment(dir, shirt);
  pc::Mesh mesh = pc::readMesh(dir / "garment.obj");
  EXPECT_EQ(mesh.F, shirt.mesh.F);
  ASSERT_TRUE(mesh.hasUV());
  for (int f = 0; f < mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      ASSERT_LT((mesh.UV.row(mesh.FUV(f, k)) - shirt.mesh.UV.row(shirt.mesh.FUV(f, k))).norm(), 1e-6);
  nlohmann::json json = pc::readJson(dir / "garment.json");
  EXPECT_EQ(json["seams"].size(), shirt.seams.size());
  EXPECT_EQ(json["face_panel"].size(), static_cast<size_t>(mesh.numFaces()));
  EXPECT_EQ(json["layouts"][0]["name"], "front");
}

// ---------------------------------------------------------------------------------------------------------------------
// Round trip: saveGarment then loadGarment gives the garment back.

namespace {

const pg::Garment& necktie() {
  static const pg::Garment tie = pg::makeNecktie();
  return tie;
}

/// Positions and UVs went through OBJ text as 32-bit floats printed with 9 digits (core::writeMesh): well within 1e-6
/// m.
constexpr double kTextTolerance = 1e-6;

/// Everything importGarment builds, compared with the garment that was saved.
void expectSameGarment(const pg::Garment& expected, const pg::Garment& actual) {
  EXPECT_EQ(actual.name, expected.name);
  ASSERT_EQ(actual.mesh.numVertices(), expected.mesh.numVertices());
  ASSERT_EQ(actual.mesh.numFaces(), expected.mesh.numFaces());
  EXPECT_EQ(actual.mesh.F, expected.mesh.F);
  EXPECT_LT((actual.mesh.V - expected.mesh.V).cwiseAbs().maxCoeff(), kTextTolerance);
  ASSERT_TRUE(actual.mesh.hasUV());
  double uvError = 0;
  for (int f = 0; f < expected.mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      uvError =
          std::max(uvError, (actual.mesh.UV.row(actual.mesh.FUV(f, k)) - expected.mesh.UV.row(expected.mesh.FUV(f, k)))
                                .cwiseAbs()
                                .maxCoeff());
  EXPECT_LT(uvError, kTextTolerance);
  EXPECT_EQ(actual.layouts, expected.layouts);
  EXPECT_EQ(actual.faceLayout, expected.faceLayout);
  EXPECT_EQ(actual.panels, expected.panels);
  EXPECT_EQ(actual.facePanel, expected.facePanel);
  // UV rows are renumbered (the OBJ merges equal vt), so vertexUV is compared by membership and value.
  ASSERT_EQ(actual.vertexUV.rows(), expected.vertexUV.rows());
  ASSERT_EQ(actual.vertexUV.cols(), expected.vertexUV.cols());
  int membershipMismatches = 0;
  double vertexUvError = 0;
  for (int v = 0; v < expected.vertexUV.rows(); ++v) {
    for (int l = 0; l < expected.vertexUV.cols(); ++l) {
      const int e = expected.vertexUV(v, l), a = actual.vertexUV(v, l);
      if ((e < 0) != (a < 0)) {
        ++membershipMismatches;
        continue;
      }
      if (e >= 0)
        vertexUvError =
            std::max(vertexUvError, (actual.mesh.UV.row(a) - expected.mesh.UV.row(e)).cwiseAbs().maxCoeff());
    }
  }
  EXPECT_EQ(membershipMismatches, 0);
  EXPECT_LT(vertexUvError, kTextTolerance);
  ASSERT_EQ(actual.seams.size(), expected.seams.size());
  for (size_t i = 0; i < expected.seams.size(); ++i) {
    SCOPED_TRACE(expected.seams[i].name);
    EXPECT_EQ(actual.seams[i].name, expected.seams[i].name);
    EXPECT_EQ(actual.seams[i].vertices, expected.seams[i].vertices);
    EXPECT_EQ(actual.seams[i].joinsLayouts, expected.seams[i].joinsLayouts);
  }
  ASSERT_EQ(actual.openings.size(), expected.openings.size());
  for (size_t i = 0; i < expected.openings.size(); ++i) {
    EXPECT_EQ(actual.openings[i].name, expected.openings[i].name);
    EXPECT_EQ(actual.openings[i].vertices, expected.openings[i].vertices) << expected.openings[i].name;
  }
  ASSERT_EQ(actual.lines.size(), expected.lines.size());
  for (size_t i = 0; i < expected.lines.size(); ++i) {
    SCOPED_TRACE(expected.lines[i].name);
    EXPECT_EQ(actual.lines[i].name, expected.lines[i].name);
    EXPECT_EQ(actual.lines[i].kind, expected.lines[i].kind);
    EXPECT_EQ(actual.lines[i].closed, expected.lines[i].closed);
    EXPECT_EQ(actual.lines[i].vertices, expected.lines[i].vertices);
  }
}

}  // namespace

TEST(GarmentImport, TShirtRoundTripsThroughItsFolder) {
  const pg::Garment& shirt = pixelcloth::testing::tshirt();
  ASSERT_EQ(shirt.numLayouts(), 2);
  ASSERT_FALSE(shirt.seams.empty());
  fs::path dir = freshDir("tshirt");
  pg::saveGarment(dir, shirt);
  expectSameGarment(shirt, pg::loadGarment(dir));
}

TEST(GarmentImport, NecktieRoundTripsThroughItsFolder) {
  fs::path dir = freshDir("necktie");
  pg::saveGarment(dir, necktie());
  expectSameGarment(necktie(), pg::loadGarment(dir));
}

TEST(GarmentImport, OptionalFieldsTakeTheirDefaults) {
  // A hand-written cage for the tie: layouts as plain strings, no face_layout, panels or face_panel (one layout,
  // one panel), no "closed" on the open band lines.
  fs::path dir = freshDir("tie");
  pg::saveGarment(dir, necktie());
  nlohmann::json saved = pc::readJson(dir / "garment.json");
  nlohmann::json lines = nlohmann::json::array();
  for (const nlohmann::json& line : saved["cage_lines"])
    lines.push_back({{"name", line["name"]}, {"kind", line["kind"]}, {"vertices", line["vertices"]}});
  nlohmann::json cage = {
      {"name", "my_tie"}, {"layouts", {"tie"}}, {"openings", saved["openings"]}, {"cage_lines", lines}};
  pc::writeJson(dir / "cage.json", cage);
  const pg::Garment tie = pg::importGarment(dir / "garment.obj", dir / "cage.json");
  EXPECT_EQ(tie.name, "my_tie");
  EXPECT_EQ(tie.layouts, std::vector<std::string>{"tie"});
  EXPECT_EQ(tie.panels, std::vector<std::string>{"my_tie"});
  EXPECT_EQ(tie.faceLayout, Eigen::VectorXi::Zero(necktie().mesh.numFaces()));
  EXPECT_EQ(tie.facePanel, Eigen::VectorXi::Zero(necktie().mesh.numFaces()));
  EXPECT_TRUE(tie.seams.empty());
  ASSERT_EQ(tie.lines.size(), necktie().lines.size());
  for (const pg::CageLine& line : tie.lines) EXPECT_FALSE(line.closed) << line.name;
  EXPECT_EQ((tie.vertexUV.array() >= 0).count(), necktie().mesh.numVertices());
}

TEST(GarmentImport, JoinsLayoutsIsComputedWhenAbsent) {
  const pg::Garment& shirt = pixelcloth::testing::tshirt();
  fs::path dir = freshDir("tshirt");
  pg::saveGarment(dir, shirt);
  nlohmann::json cage = pc::readJson(dir / "garment.json");
  for (nlohmann::json& seam : cage["seams"]) seam.erase("joins_layouts");
  pc::writeJson(dir / "garment.json", cage);
  const pg::Garment imported = pg::loadGarment(dir);
  ASSERT_EQ(imported.seams.size(), shirt.seams.size());
  int stitched = 0;
  for (size_t i = 0; i < shirt.seams.size(); ++i) {
    EXPECT_EQ(imported.seams[i].joinsLayouts, shirt.seams[i].joinsLayouts) << shirt.seams[i].name;
    stitched += shirt.seams[i].joinsLayouts;
  }
  EXPECT_GT(stitched, 0);
  EXPECT_LT(stitched, static_cast<int>(shirt.seams.size())) << "the armholes are sewn inside one layout";
}

// ---------------------------------------------------------------------------------------------------------------------
// Bad input: each refused with a message naming the file and the fault.

namespace {

/// A saved T-shirt folder whose garment.json a test edits.
class GarmentImportRefuses : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = freshDir("tshirt");
    pg::saveGarment(dir_, shirt());
    cage_ = pc::readJson(jsonPath());
  }
  static const pg::Garment& shirt() { return pixelcloth::testing::tshirt(); }
  fs::path objPath() const { return dir_ / "garment.obj"; }
  fs::path jsonPath() const { return dir_ / "garment.json"; }

  /// Writes the edited cage back and returns the message loadGarment refuses it with.
  std::string errorAfterEdit() {
    pc::writeJson(jsonPath(), cage_);
    return inputErrorOf([&] { pg::loadGarment(dir_); });
  }

  /// Vertices on a seam, an opening or a cage line other than `lineName`.
  static std::set<int> onCurvesOtherThan(const std::string& lineName) {
    std::set<int> vertices;
    for (const pg::Seam& s : shirt().seams) vertices.insert(s.vertices.begin(), s.vertices.end());
    for (const pg::Opening& o : shirt().openings) vertices.insert(o.vertices.begin(), o.vertices.end());
    for (const pg::CageLine& l : shirt().lines)
      if (l.name != lineName) vertices.insert(l.vertices.begin(), l.vertices.end());
    return vertices;
  }

  /// The first half of centre_front, cut at a vertex near its middle that is on no other curve.
  static std::vector<int> centreFrontCut() {
    const pg::CageLine* line = shirt().findLine("centre_front");
    if (line == nullptr || line->closed) return {};
    const std::set<int> elsewhere = onCurvesOtherThan(line->name);
    size_t keep = line->vertices.size() / 2;
    while (keep < line->vertices.size() && elsewhere.count(line->vertices[keep - 1])) ++keep;
    if (keep == line->vertices.size()) return {};
    return std::vector<int>(line->vertices.begin(), line->vertices.begin() + keep);
  }

  nlohmann::json& item(const std::string& list, const std::string& name) {
    for (nlohmann::json& entry : cage_[list])
      if (entry["name"] == name) return entry;
    ADD_FAILURE() << "no " << list << " entry '" << name << "'";
    static nlohmann::json none;
    return none;
  }

  fs::path dir_;
  nlohmann::json cage_;
};

::testing::AssertionResult mentions(const std::string& message, const std::vector<std::string>& parts) {
  for (const std::string& part : parts) {
    if (message.find(part) == std::string::npos)
      return ::testing::AssertionFailure() << "the message does not mention '" << part << "': " << message;
  }
  return ::testing::AssertionSuccess() << message;
}

std::string vertexName(int v) { return "vertex " + std::to_string(v) + " (OBJ vertex " + std::to_string(v + 1) + ")"; }

}  // namespace

TEST_F(GarmentImportRefuses, MissingObj) {
  const fs::path missing = dir_ / "nowhere.obj";
  const std::string message = inputErrorOf([&] { pg::importGarment(missing, jsonPath()); });
  EXPECT_TRUE(mentions(message, {missing.string(), "no such file"}));
}

TEST_F(GarmentImportRefuses, ObjWithoutUvs) {
  pc::Mesh bare;
  bare.V = shirt().mesh.V;
  bare.F = shirt().mesh.F;
  const fs::path obj = dir_ / "bare.obj";
  pc::writeMesh(obj, bare);
  const std::string message = inputErrorOf([&] { pg::importGarment(obj, jsonPath()); });
  EXPECT_TRUE(mentions(message, {obj.string(), "no texture coordinates"}));
}

TEST_F(GarmentImportRefuses, MissingJson) {
  const fs::path missing = dir_ / "nowhere.json";
  const std::string message = inputErrorOf([&] { pg::importGarment(objPath(), missing); });
  EXPECT_TRUE(mentions(message, {missing.string()}));
}

TEST_F(GarmentImportRefuses, SeamStepThatIsNoEdge) {
  const pg::Seam& seam = shirt().seams.front();
  const int from = seam.vertices[0];
  // The vertex farthest from the seam's start shares no edge with it.
  int far = 0;
  (shirt().mesh.V.rowwise() - shirt().mesh.V.row(from)).rowwise().squaredNorm().maxCoeff(&far);
  ASSERT_EQ(std::count(seam.vertices.begin(), seam.vertices.end(), far), 0);
  item("seams", seam.name)["vertices"][1] = far;
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), "seam '" + seam.name + "'", vertexName(from),
                                          vertexName(far), "share no edge"}));
}

TEST_F(GarmentImportRefuses, VertexIndexOutOfRange) {
  const int numVertices = shirt().mesh.numVertices();
  item("cage_lines", "chest")["vertices"][3] = numVertices;
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), "cage line 'chest'", std::to_string(numVertices),
                                          "has " + std::to_string(numVertices) + " vertices"}));
}

TEST_F(GarmentImportRefuses, NegativeVertexIndex) {
  item("openings", "hem")["vertices"][0] = -1;
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), "opening 'hem'", "is -1"}));
}

TEST_F(GarmentImportRefuses, UnknownCageLineKind) {
  item("cage_lines", "waist")["kind"] = "zigzag";
  EXPECT_TRUE(mentions(errorAfterEdit(),
                       {jsonPath().string(), "cage line 'waist'", "'zigzag'", "loop", "centre_line", "split"}));
}

TEST_F(GarmentImportRefuses, FaceLayoutOfTheWrongLength) {
  cage_["face_layout"].erase(cage_["face_layout"].size() - 1);
  const int numFaces = shirt().mesh.numFaces();
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), "face_layout", std::to_string(numFaces - 1) + " entries",
                                          "(" + std::to_string(numFaces) + ")"}));
}

TEST_F(GarmentImportRefuses, MissingFaceLayoutWithTwoLayouts) {
  cage_.erase("face_layout");
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), "missing field 'face_layout'", "front", "back"}));
}

TEST_F(GarmentImportRefuses, CageLineThatStopsInsideAPatch) {
  const std::vector<int> half = centreFrontCut();
  ASSERT_GE(half.size(), 2u);
  item("cage_lines", "centre_front")["vertices"] = half;
  EXPECT_TRUE(mentions(errorAfterEdit(),
                       {jsonPath().string(), "cage line 'centre_front'", vertexName(half.back()), "inside a patch"}));
}

TEST_F(GarmentImportRefuses, CageLineEndingOnALoopInsideAPatch) {
  // centre_front cut near its middle and ended on a tiny closed loop (one triangle's outline) there: its end lies on
  // another curve, yet the cut line still does not split the patch it runs in.
  const std::vector<int> half = centreFrontCut();
  ASSERT_GE(half.size(), 2u);
  const int end = half.back(), before = half[half.size() - 2];
  const Eigen::MatrixX3i& F = shirt().mesh.F;
  int face = -1;
  for (int f = 0; f < F.rows() && face < 0; ++f)
    if ((F.row(f).array() == end).any() && !(F.row(f).array() == before).any()) face = f;
  ASSERT_GE(face, 0);
  int k = 0;
  while (F(face, k) != end) ++k;
  item("cage_lines", "centre_front")["vertices"] = half;
  cage_["cage_lines"].push_back({{"name", "button"},
                                 {"kind", "split"},
                                 {"closed", true},
                                 {"vertices", {end, F(face, (k + 1) % 3), F(face, (k + 2) % 3)}}});
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), "cage line 'centre_front'", "does not close a patch"}));
}

TEST_F(GarmentImportRefuses, BoundaryEdgeInNoOpening) {
  nlohmann::json openings = nlohmann::json::array();
  for (const nlohmann::json& opening : cage_["openings"])
    if (opening["name"] != "hem") openings.push_back(opening);
  ASSERT_EQ(openings.size() + 1, cage_["openings"].size());
  cage_["openings"] = openings;
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), objPath().string(), "belong to no opening"}));
}

TEST_F(GarmentImportRefuses, OpeningAgainstTheBoundary) {
  std::vector<int> hem = item("openings", "hem")["vertices"].get<std::vector<int>>();
  std::reverse(hem.begin(), hem.end());
  item("openings", "hem")["vertices"] = hem;
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), "opening 'hem'", "runs against the boundary"}));
}

TEST_F(GarmentImportRefuses, RepeatedName) {
  cage_["seams"].push_back(cage_["seams"][0]);
  EXPECT_TRUE(mentions(errorAfterEdit(),
                       {jsonPath().string(), "seams", cage_["seams"][0]["name"].get<std::string>(), "used twice"}));
}

TEST_F(GarmentImportRefuses, WrongJoinsLayouts) {
  item("seams", "armhole_front_left")["joins_layouts"] = true;
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), "seam 'armhole_front_left'", "joins_layouts"}));
}

TEST_F(GarmentImportRefuses, LayoutsMeetingOffASeam) {
  nlohmann::json seams = nlohmann::json::array();
  for (const nlohmann::json& seam : cage_["seams"])
    if (seam["name"] != shirt().seams.front().name) seams.push_back(seam);
  cage_["seams"] = seams;
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), "lies on no seam", "'front'", "'back'"}));
}

TEST_F(GarmentImportRefuses, TwoUvsOfOneVertexInOneLayout) {
  pc::Mesh mesh = shirt().mesh;
  const int f = 10, v = mesh.F(f, 0);
  mesh.UV.conservativeResize(mesh.UV.rows() + 1, 2);
  mesh.UV.row(mesh.UV.rows() - 1) = mesh.UV.row(mesh.FUV(f, 0)) + Eigen::RowVector2d(0.001, 0.0);
  mesh.FUV(f, 0) = static_cast<int>(mesh.UV.rows() - 1);
  pc::writeMesh(objPath(), mesh);
  EXPECT_TRUE(mentions(inputErrorOf([&] { pg::loadGarment(dir_); }),
                       {objPath().string(), "OBJ vertex " + std::to_string(v + 1), "two different UVs",
                        "'" + shirt().layouts[shirt().faceLayout[f]] + "'"}));
}

TEST_F(GarmentImportRefuses, DegenerateUvTriangle) {
  // Face 1's first corner moved onto the midpoint of the other two, on a UV row of its own.
  pc::Mesh mesh = shirt().mesh;
  mesh.UV.conservativeResize(mesh.UV.rows() + 1, 2);
  mesh.UV.row(mesh.UV.rows() - 1) = 0.5 * (mesh.UV.row(mesh.FUV(0, 1)) + mesh.UV.row(mesh.FUV(0, 2)));
  mesh.FUV(0, 0) = static_cast<int>(mesh.UV.rows() - 1);
  pc::writeMesh(objPath(), mesh);
  EXPECT_TRUE(mentions(inputErrorOf([&] { pg::loadGarment(dir_); }), {objPath().string(), "face 1 ", "degenerate"}));
}

TEST_F(GarmentImportRefuses, JsonOfAnotherMesh) {
  cage_["mesh"]["vertices"] = shirt().mesh.numVertices() + 1;
  EXPECT_TRUE(mentions(errorAfterEdit(), {jsonPath().string(), objPath().string(), "'vertices'"}));
}

TEST_F(GarmentImportRefuses, BrokenJsonText) {
  pc::writeTextAtomically(jsonPath(), "{\"name\": \"tshirt\", \"layouts\": [\n");
  EXPECT_TRUE(mentions(inputErrorOf([&] { pg::loadGarment(dir_); }), {jsonPath().string(), "invalid JSON"}));
}

// ---------------------------------------------------------------------------------------------------------------------
// Templates by name

TEST(GarmentTemplates, NamesAreTheBuiltInTemplates) {
  EXPECT_EQ(pg::templateNames(), (std::vector<std::string>{"tshirt", "necktie"}));
}

TEST(GarmentTemplates, MakeGarmentBuildsTheNamedTemplate) {
  const pg::Garment shirt = pg::makeGarment("tshirt");
  const pg::Garment& reference = pixelcloth::testing::tshirt();  // makeTShirt() with default options
  EXPECT_EQ(shirt.name, "tshirt");
  EXPECT_EQ(shirt.mesh.numVertices(), reference.mesh.numVertices());
  EXPECT_EQ(shirt.mesh.F, reference.mesh.F);
  const pg::Garment tie = pg::makeGarment("necktie");
  EXPECT_EQ(tie.name, "necktie");
  EXPECT_EQ(tie.mesh.numVertices(), necktie().mesh.numVertices());
  EXPECT_EQ(tie.mesh.F, necktie().mesh.F);
}

TEST(GarmentTemplates, UnknownNameIsRefusedListingTheKnownOnes) {
  const std::string message = inputErrorOf([] { pg::makeGarment("skirt", "cage --garment"); });
  EXPECT_TRUE(mentions(message, {"cage --garment", "'skirt'", "tshirt", "necktie"}));
}
