// What a garment carries besides its mesh and cage (pose joints, pins, image size, offset frame, loss weights): set by
// the templates, written to garment.json, read back under any name, and what --garment resolves to. No stage may
// choose behaviour by a garment's name: a scan of the sources checks it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "pixelcloth/core/json_io.h"
#include "pixelcloth/garment/garment.h"
#include "support/test_util.h"

namespace {

namespace fs = std::filesystem;
namespace pg = pixelcloth::garment;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

bool mentions(const std::string& message, const std::vector<std::string>& parts) {
  for (const std::string& part : parts)
    if (message.find(part) == std::string::npos) {
      ADD_FAILURE() << "'" << part << "' not in: " << message;
      return false;
    }
  return true;
}

const pg::Garment& smallNecktie() {
  static const pg::Garment tie = [] {
    pg::NecktieOptions options;
    options.targetVertices = 300;
    return pg::makeNecktie(options);
  }();
  return tie;
}

}  // namespace

TEST(GarmentTraits, TemplatesCarryThePapersSettings) {
  const pg::Garment& tie = smallNecktie();
  EXPECT_EQ(tie.traits.poseSize(), 36);
  EXPECT_FALSE(tie.traits.armsDrive());
  EXPECT_EQ(tie.traits.imageWidth, 64);
  EXPECT_EQ(tie.traits.imageHeight, 256);
  EXPECT_TRUE(tie.traits.rootFrameOffsets);
  EXPECT_DOUBLE_EQ(tie.traits.edgeLossWeight, 0.1);
  // The knot end: every pinned vertex within 4 cm of the top, and some are.
  ASSERT_FALSE(tie.traits.pinned.empty());
  const double top = tie.mesh.V.col(1).maxCoeff();
  for (int v : tie.traits.pinned) EXPECT_GT(tie.mesh.V(v, 1), top - 0.04);
  const pg::GarmentTraits shirt = pg::templateTraits("tshirt");
  EXPECT_EQ(shirt.poseSize(), 90);
  EXPECT_TRUE(shirt.armsDrive());
  EXPECT_TRUE(shirt.pinned.empty());
  EXPECT_FALSE(shirt.rootFrameOffsets);
}

TEST(GarmentTraits, TravelWithTheFolderUnderAnyName) {
  const fs::path dir = freshDir("tie");
  pg::Garment tie = smallNecktie();
  tie.name = "bow";
  pg::saveGarment(dir, tie);
  const pg::Garment back = pg::resolveGarment(dir.string());
  EXPECT_EQ(back.name, "bow");
  EXPECT_EQ(back.traits.poseJoints, 4);
  EXPECT_EQ(back.traits.pinned, tie.traits.pinned);
  EXPECT_EQ(back.traits.imageWidth, 64);
  EXPECT_TRUE(back.traits.rootFrameOffsets);
  EXPECT_DOUBLE_EQ(back.traits.normalLossWeight, 0.1);
}

TEST(GarmentTraits, AFolderWithoutTraitsIsReadAsItsTemplateWasWritten) {
  const fs::path dir = freshDir("old");
  pg::saveGarment(dir, smallNecktie());
  nlohmann::json json = pixelcloth::core::readJson(dir / "garment.json");
  json.erase("traits");
  pixelcloth::core::writeJson(dir / "garment.json", json);
  const pg::Garment old = pg::loadGarment(dir);
  EXPECT_EQ(old.traits.poseJoints, 4);
  EXPECT_EQ(old.traits.pinned, smallNecktie().traits.pinned);
  // Under another name it is an ordinary garment: the defaults.
  json["name"] = "scarf";
  pixelcloth::core::writeJson(dir / "garment.json", json);
  EXPECT_EQ(pg::loadGarment(dir).traits.poseJoints, 10);
  EXPECT_TRUE(pg::loadGarment(dir).traits.pinned.empty());
}

TEST(GarmentTraits, BadTraitsAreRefusedNamingTheFileAndField) {
  const fs::path dir = freshDir("bad");
  pg::saveGarment(dir, smallNecktie());
  const nlohmann::json good = pixelcloth::core::readJson(dir / "garment.json");
  const std::string file = (dir / "garment.json").string();
  auto refusal = [&](const char* field, const nlohmann::json& value) {
    nlohmann::json json = good;
    json["traits"][field] = value;
    pixelcloth::core::writeJson(dir / "garment.json", json);
    return inputErrorOf([&] { pg::loadGarment(dir); });
  };
  const int n = smallNecktie().mesh.numVertices();
  EXPECT_TRUE(mentions(refusal("pinned", {0, n}), {file, "pinned[1]", std::to_string(n)}));
  EXPECT_TRUE(mentions(refusal("pose_joints", {"neck", "spine"}), {file, "pose_joints", "lower_back"}));
  EXPECT_TRUE(mentions(refusal("image_size", {64}), {file, "image_size"}));
  EXPECT_TRUE(mentions(refusal("image_size", {0, 256}), {file, "image size"}));
  EXPECT_TRUE(mentions(refusal("offset_frame", "world"), {file, "offset_frame", "local or root"}));
  EXPECT_TRUE(mentions(refusal("edge_loss_weight", -1), {file, "edge loss weight"}));
}

TEST(GarmentTraits, ResolveTakesATemplateNameOrAGarmentFolder) {
  EXPECT_EQ(pg::resolveGarment("necktie").name, "necktie");
  const fs::path dir = freshDir("resolve");
  EXPECT_TRUE(mentions(inputErrorOf([&] { pg::resolveGarment("skirt", "dress --garment"); }),
                       {"dress --garment", "skirt", "tshirt", "necktie", "garment folder"}));
  EXPECT_TRUE(
      mentions(inputErrorOf([&] { pg::resolveGarment(dir.string()); }), {dir.string(), "garment.obj", "garment.json"}));
  // A folder called like a template is the template unless it is a garment folder.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir);
  fs::create_directories("necktie");
  EXPECT_EQ(pg::resolveGarment("necktie").traits.poseJoints, 4);
  pg::Garment bow = smallNecktie();
  bow.name = "bow";
  pg::saveGarment("necktie", bow);
  EXPECT_EQ(pg::resolveGarment("necktie").name, "bow");
  fs::current_path(cwd);
  std::ofstream(dir / "file.obj") << "v 0 0 0\n";
  EXPECT_TRUE(
      mentions(inputErrorOf([&] { pg::resolveGarment((dir / "file.obj").string()); }), {"file.obj", "not a garment"}));
}

// DESIGN.md: the templates are chosen by name in one place (garment/src/templates.cpp); every other stage reads what
// it needs from the garment it is given. A comparison with a template's name anywhere else in the product's sources
// would send an imported garment down another path than the template it copies.
TEST(GarmentTraits, NoStageOutsideTheTemplatesComparesAGarmentName) {
  const fs::path root = fs::path(PIXELCLOTH_TEST_ASSETS).parent_path().parent_path();
  const std::regex comparison(R"re(([!=]=\s*"(tshirt|necktie)")|("(tshirt|necktie)"\s*[!=]=))re");
  const std::regex nameComparison(R"re((\.name\s*[!=]=\s*"[a-z_]+")|("[a-z_]+"\s*[!=]=\s*[a-z_]+\.name\b))re");
  int files = 0;
  for (const char* module : {"core", "body", "garment", "cage", "patches", "data", "sim", "recon", "learn", "stitch",
                             "motion", "eval", "viz", "apps"}) {
    if (!fs::is_directory(root / module)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / module)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".cpp" && ext != ".h") continue;
      ++files;
      if (entry.path().filename() == "templates.cpp") continue;
      std::ifstream in(entry.path());
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        EXPECT_FALSE(std::regex_search(line, comparison))
            << entry.path().string() << ":" << number << " compares with a template's name: " << line;
        EXPECT_FALSE(std::regex_search(line, nameComparison) && line.find("garment") != std::string::npos)
            << entry.path().string() << ":" << number << " compares a garment's name: " << line;
      }
    }
  }
  EXPECT_GT(files, 100) << "the scan found too few sources under " << root;
}

TEST(TShirtGrading, ScalesEveryPatternLengthAndKeepsThePlacement) {
  const pg::TShirtOptions m;
  const pg::TShirtOptions l = m.graded(pg::sizeGrade("L"));
  EXPECT_DOUBLE_EQ(l.length, 1.06 * m.length);
  EXPECT_DOUBLE_EQ(l.halfWidth, 1.06 * m.halfWidth);
  EXPECT_DOUBLE_EQ(l.sleeveHemHeight, 1.06 * m.sleeveHemHeight);
  EXPECT_DOUBLE_EQ(l.neckSideHeight, m.neckSideHeight);
  EXPECT_EQ(l.targetVertices, m.targetVertices);
  for (const char* size : {"xs", "S", "M", "L", "XL", "XXL"}) EXPECT_NO_THROW(m.graded(pg::sizeGrade(size)).validate());
  EXPECT_EQ(pg::nearestSize(1.0), "M");
  EXPECT_EQ(pg::nearestSize(1.5), "XXL");
  EXPECT_TRUE(mentions(inputErrorOf([] { pg::sizeGrade("XXXL"); }), {"XXXL", "XS", "XXL", "--grade"}));
  EXPECT_TRUE(mentions(inputErrorOf([&] { m.graded(3.0); }), {"grade 3", "0.6 to 1.6"}));
}

TEST(TShirtGrading, AGradedShirtHasThePatternAreaOfItsGrade) {
  pg::TShirtOptions options;
  options.targetVertices = 800;
  const pg::Garment m = pg::makeTShirt(options), xl = pg::makeTShirt(options.graded(1.12));
  auto uvArea = [](const pg::Garment& g) {
    double area = 0;
    for (int f = 0; f < g.mesh.numFaces(); ++f) {
      const Eigen::Vector2d a = g.mesh.UV.row(g.mesh.FUV(f, 0)), b = g.mesh.UV.row(g.mesh.FUV(f, 1)),
                            c = g.mesh.UV.row(g.mesh.FUV(f, 2));
      area += 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    }
    return area;
  };
  EXPECT_NEAR(uvArea(xl) / uvArea(m), 1.12 * 1.12, 0.01);
  EXPECT_EQ(xl.seams.size(), m.seams.size());
  EXPECT_EQ(xl.lines.size(), m.lines.size());
}

// A template's folder remembers the options it was built with, so loading it gives the exact mesh back rather than
// the OBJ's 9-digit numbers: a dataset's stages see the very garment it was simulated with. An edited OBJ is no
// longer the template, and is read as it is.
TEST(GarmentTraits, ATemplateFolderLoadsBackExactlyUnlessItsObjWasEdited) {
  const fs::path dir = freshDir("exact");
  pg::TShirtOptions options;
  options.targetVertices = 800;
  options.halfWidth = 0.2712345678901;
  pg::Garment shirt = pg::makeTShirt(options);
  shirt.name = "renamed";
  pg::saveGarment(dir, shirt);
  const pg::Garment back = pg::loadGarment(dir);
  EXPECT_EQ(back.name, "renamed");
  EXPECT_EQ(back.mesh.V, shirt.mesh.V);
  ASSERT_EQ(back.mesh.FUV.rows(), shirt.mesh.FUV.rows());
  for (int f = 0; f < shirt.mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(back.mesh.UV.row(back.mesh.FUV(f, k)), shirt.mesh.UV.row(shirt.mesh.FUV(f, k))) << "face " << f + 1;
  EXPECT_EQ(back.recipe, shirt.recipe);

  pg::Garment moved = shirt;
  moved.mesh.V.col(2).array() += 0.01;  // edited after it was built: its own garment now
  pg::saveGarment(dir, moved);
  const pg::Garment edited = pg::loadGarment(dir);
  EXPECT_TRUE(edited.recipe.is_null());
  EXPECT_NEAR((edited.mesh.V - moved.mesh.V).cwiseAbs().maxCoeff(), 0.0, 1e-6);

  nlohmann::json json = pixelcloth::core::readJson(dir / "garment.json");
  json["template"] = {{"name", "tshirt"}, {"options", {{"length", 0.67}}}};
  pixelcloth::core::writeJson(dir / "garment.json", json);
  EXPECT_TRUE(mentions(inputErrorOf([&] { pg::loadGarment(dir); }), {"garment.json: template", "target_vertices"}));
}
