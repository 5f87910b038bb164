// `pixelcloth garment --import OBJ [--cage JSON] --out DIR`, run as a program: a garment folder the template form wrote
// comes back through the import form, with its cage or with the cage found automatically, and a broken cage or a
// garment of the wrong size is refused with exit code 2 before anything is written.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "pixelcloth/core/json_io.h"
#include "pixelcloth/garment/obj_import.h"
#include "support/cli.h"
#include "support/test_util.h"

namespace {

namespace fs = std::filesystem;
using pixelcloth::testing::CliRun;
using pixelcloth::testing::filesUnder;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::readFile;
using pixelcloth::testing::refused;
using pixelcloth::testing::runPixelcloth;

bool isPngFile(const fs::path& path) { return readFile(path).rfind("\x89PNG\r\n\x1a\n", 0) == 0; }

/// A necktie folder written by the template form, shared by the tests of this file.
class GarmentImportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = freshDir("work");
    const CliRun run = runPixelcloth({"garment", "necktie", "--out", (work_ / "A").string()});
    ASSERT_EQ(run.status, 0) << run;
  }
  fs::path work_;
};

}  // namespace

TEST_F(GarmentImportCli, ImportsAnExportedNecktie) {
  const fs::path a = work_ / "A", b = work_ / "B";
  const CliRun run = runPixelcloth({"garment", "--import", (a / "garment.obj").string(), "--cage",
                                    (a / "garment.json").string(), "--out", b.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json exported = pixelcloth::core::readJson(a / "garment.json");
  const nlohmann::json imported = pixelcloth::core::readJson(b / "garment.json");
  EXPECT_EQ(imported.at("mesh").at("faces"), exported.at("mesh").at("faces"));
  EXPECT_EQ(imported.at("face_layout").size(), exported.at("face_layout").size());
  EXPECT_EQ(imported.at("cage_lines").size(), exported.at("cage_lines").size());
  EXPECT_EQ(imported.at("openings"), exported.at("openings"));
  EXPECT_TRUE(isPngFile(b / "pattern.png"));
  EXPECT_TRUE(isPngFile(b / "garment.png"));
  EXPECT_EQ(filesUnder(b).size(), 4u);
}

TEST_F(GarmentImportCli, BrokenCageIsRefusedAndNothingIsWritten) {
  const fs::path a = work_ / "A", b2 = work_ / "B2";
  nlohmann::json cage = pixelcloth::core::readJson(a / "garment.json");
  ASSERT_FALSE(cage.at("cage_lines").empty());
  cage["cage_lines"][0]["kind"] = "zigzag";
  const fs::path broken = work_ / "broken.json";
  pixelcloth::core::writeJson(broken, cage);
  const CliRun run = runPixelcloth(
      {"garment", "--import", (a / "garment.obj").string(), "--cage", broken.string(), "--out", b2.string()});
  EXPECT_TRUE(refused(run, {broken.string(), "zigzag"}));
  EXPECT_TRUE(filesUnder(b2).empty());
}

TEST_F(GarmentImportCli, ImportAndTemplateTogetherOrNeitherAreRefused) {
  const fs::path a = work_ / "A", out = work_ / "C";
  EXPECT_TRUE(refused(runPixelcloth({"garment", "necktie", "--import", (a / "garment.obj").string(), "--cage",
                                     (a / "garment.json").string(), "--out", out.string()}),
                      {"necktie", "--import"}));
  EXPECT_TRUE(refused(runPixelcloth({"garment", "--out", out.string()}), {"tshirt", "necktie", "--import"}));
  EXPECT_TRUE(refused(runPixelcloth({"garment", "necktie", "--up", "z", "--out", out.string()}), {"--up", "--import"}));
  EXPECT_TRUE(filesUnder(out).empty());
}

TEST_F(GarmentImportCli, ImportWithoutACageFindsTheOutline) {
  const fs::path a = work_ / "A", d = work_ / "D";
  const CliRun run =
      runPixelcloth({"garment", "--import", (a / "garment.obj").string(), "--name", "tie", "--out", d.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json imported = pixelcloth::core::readJson(d / "garment.json");
  EXPECT_EQ(imported.at("name"), "tie");
  ASSERT_EQ(imported.at("openings").size(), 1u);
  EXPECT_EQ(imported.at("openings")[0].at("name"), "outline");
  EXPECT_EQ(imported.at("openings")[0].at("vertices").size(),
            pixelcloth::core::readJson(a / "garment.json").at("openings")[0].at("vertices").size());
  EXPECT_TRUE(imported.at("seams").empty());
  EXPECT_EQ(filesUnder(d).size(), 4u);
}

TEST_F(GarmentImportCli, ImportOfTheWrongSizeIsRefusedNamingTheScale) {
  const fs::path a = work_ / "A", e = work_ / "E";
  const CliRun run =
      runPixelcloth({"garment", "--import", (a / "garment.obj").string(), "--scale", "100", "--out", e.string()});
  EXPECT_TRUE(refused(run, {(a / "garment.obj").string(), "m tall", "expected 0.05 to 3 m", "use --scale 1"}));
  EXPECT_TRUE(filesUnder(e).empty());
}

TEST(GarmentFitCli, ATShirtObjFittedToTheMannequinComesBackWithTheTemplatesCageLinesAnd28Patches) {
  const fs::path work = freshDir("fit");
  pixelcloth::garment::ObjExportOptions file;
  file.groups = true;
  pixelcloth::garment::exportGarmentObj(pixelcloth::garment::makeTShirt(), work / "shirt.obj", file);
  const CliRun run = runPixelcloth({"garment", "--import", (work / "shirt.obj").string(), "--fit-to", "mannequin",
                                    "--out", (work / "fitted").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_NE(run.err.find("28 patches"), std::string::npos) << run;
  const nlohmann::json fitted = pixelcloth::core::readJson(work / "fitted" / "garment.json");
  std::vector<std::string> lines;
  for (const nlohmann::json& line : fitted.at("cage_lines")) lines.push_back(line.at("name"));
  std::sort(lines.begin(), lines.end());
  EXPECT_EQ(lines, (std::vector<std::string>{"bicep_left", "bicep_right", "centre_back", "centre_front", "chest",
                                             "side_panel_back_left", "side_panel_back_right", "side_panel_front_left",
                                             "side_panel_front_right", "waist"}));
  EXPECT_EQ(filesUnder(work / "fitted").size(), 4u);
}

TEST(GarmentFitCli, FitToATemplateOrAMissingBodyIsRefusedAndNothingIsWritten) {
  const fs::path work = freshDir("fit_refused");
  EXPECT_TRUE(refused(runPixelcloth({"garment", "tshirt", "--fit-to", "mannequin", "--out", (work / "A").string()}),
                      {"--fit-to", "template"}));
  EXPECT_TRUE(filesUnder(work / "A").empty());
  pixelcloth::garment::exportGarmentObj(pixelcloth::garment::makeNecktie(), work / "tie.obj");
  const fs::path nowhere = work / "no_such_body";
  EXPECT_TRUE(refused(runPixelcloth({"garment", "--import", (work / "tie.obj").string(), "--fit-to",
                                     nowhere.string(), "--out", (work / "B").string()}),
                      {nowhere.string()}));
  EXPECT_TRUE(filesUnder(work / "B").empty());
}

TEST(GarmentImportCliHelp, ListsEveryOptionWithItsDefault) {
  const CliRun run = runPixelcloth({"garment", "--help"});
  ASSERT_EQ(run.status, 0) << run;
  for (const std::string option : {"kind", "--import", "--cage", "--name", "--up", "--scale", "--translate", "--fit-to", "--out",
                                   "--vertices", "tshirt", "necktie", "3000"})
    EXPECT_NE(run.out.find(option), std::string::npos) << option << run;
}
