// pixelcloth garment, bases, cage and dress on the templates; bad names and folders refused.
#include "cli_fixtures.h"

namespace pixelcloth::apps {
namespace {

// ---------------------------------------------------------------------------------------------------------------------
// garment

TEST_F(CliTest, GarmentTShirtWritesMeshWithUvs) {
  fs::path out = dir("out") / "tshirt";
  CliRun run = runPixelcloth({"garment", "tshirt", "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  ASSERT_TRUE(fs::is_regular_file(out / "garment.obj")) << listing(filesUnder(out));
  int texcoords = 0, faces = 0;
  for (const std::string& line : lines(readFile(out / "garment.obj"))) {
    texcoords += startsWith(line, "vt ");
    faces += startsWith(line, "f ");
  }
  EXPECT_GT(texcoords, 0);
  EXPECT_GT(faces, 0);
  EXPECT_NO_THROW(nlohmann::json::parse(readFile(out / "garment.json")));
  EXPECT_TRUE(isPng(out / "pattern.png"));
  EXPECT_TRUE(isPng(out / "garment.png"));
  EXPECT_TRUE(noTemporaries(out));
}

TEST_F(CliTest, GarmentRefusesUnknownKind) {
  fs::path out = dir("out") / "skirt";
  EXPECT_TRUE(refused(runPixelcloth({"garment", "skirt", "--out", out.string()}), {"skirt", "tshirt", "necktie"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliTest, GarmentRefusesFileAsOutputFolder) {
  fs::path work = dir("work");
  fs::path file = work / "F";
  writeFile(file, "not a folder\n");
  EXPECT_TRUE(refused(runPixelcloth({"garment", "tshirt", "--out", file.string()}), {file.string(), "not a folder"}));
  EXPECT_EQ(readFile(file), "not a folder\n");
  EXPECT_EQ(filesUnder(work), std::vector<std::string>{"F"});
}

// ---------------------------------------------------------------------------------------------------------------------
// bases

TEST_F(CliTest, BasesWritesFiguresAndContactSheet) {
  fs::path out = dir("out") / "bases";
  CliRun run = runPixelcloth({"bases", "--figures", out.string(), "--cells", "6", "--size", "48"});
  ASSERT_EQ(run.status, 0) << run;
  for (const std::string shape : {"one_bump", "two_bumps", "sine", "s_curve"})
    for (const std::string kind : {"_iso", "_aniso"}) {
      EXPECT_TRUE(isPng(out / (shape + kind + ".png"))) << shape + kind;
      EXPECT_TRUE(isPng(out / (shape + kind + "_3d.png"))) << shape + kind;
      EXPECT_EQ(core::readMesh(out / (shape + kind + ".obj")).numFaces(), 4 * 6 * 6) << shape + kind;
    }
  EXPECT_TRUE(isPng(out / "bases.png"));
  EXPECT_TRUE(noTemporaries(out));
}

TEST_F(CliTest, BasesRefusesRatioOutsideUnitInterval) {
  fs::path out = dir("out") / "bases";
  EXPECT_TRUE(refused(runPixelcloth({"bases", "--figures", out.string(), "--ratio", "0"}), {"ratio", "(0, 1]"}));
}

// cage

TEST_F(CliTest, CageWritesCurvesPatchesAndPicture) {
  fs::path out = dir("out") / "cage";
  CliRun run = runPixelcloth({"cage", "--garment", "tshirt", "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json cage = nlohmann::json::parse(readFile(out / "cage.json"));
  EXPECT_EQ(cage.at("garment"), "tshirt");
  EXPECT_GT(cage.at("curves").size(), 20u);
  const nlohmann::json patches = nlohmann::json::parse(readFile(out / "patches.json")).at("patches");
  ASSERT_EQ(patches.size(), 28u);
  for (const auto& patch : patches) {
    EXPECT_TRUE(patch.at("side") == "front" || patch.at("side") == "back");
    EXPECT_GT(patch.at("boundary").size(), 3u);
    EXPECT_GT(patch.at("vertices").size(), patch.at("boundary").size());
    EXPECT_EQ(patch.at("bbox_px_512").size(), 2u);
  }
  EXPECT_TRUE(isPng(out / "cage.png"));
  EXPECT_TRUE(noTemporaries(out));
}

TEST_F(CliTest, CageRefusesUnknownGarment) {
  fs::path out = dir("out") / "skirt";
  EXPECT_TRUE(refused(runPixelcloth({"cage", "--garment", "skirt", "--out", out.string()}), {"skirt"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

// ---------------------------------------------------------------------------------------------------------------------
// dress

TEST_F(CliBodyTest, DressWritesShirtOnBodyWithLessAreaDistortionAfterRelaxation) {
  fs::path out = dir("out") / "dressed";
  CliRun run = runPixelcloth({"dress", "--garment", "tshirt", "--body", body_.string(), "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(filesUnder(out),
            (std::vector<std::string>{"area_distortion.png", "dressed.obj", "dressed.png", "dressing.json"}));
  EXPECT_TRUE(isPng(out / "area_distortion.png"));
  EXPECT_TRUE(isPng(out / "dressed.png"));
  const core::Mesh dressed = core::readMesh(out / "dressed.obj");
  const garment::Garment shirt = garment::makeTShirt();
  EXPECT_EQ(dressed.numVertices(), shirt.mesh.numVertices());
  EXPECT_TRUE(dressed.hasUV());
  const nlohmann::json report = nlohmann::json::parse(readFile(out / "dressing.json"));
  EXPECT_EQ(report.at("garment"), "tshirt");
  EXPECT_GT(report.at("relax_iterations").get<int>(), 0);
  EXPECT_EQ(report.at("inside_after_relaxation").get<int>(), 0);
  const auto spread = [&](const char* key) {
    return std::log2(report.at(key).at("p95").get<double>()) - std::log2(report.at(key).at("p5").get<double>());
  };
  EXPECT_LT(spread("area_ratio_after"), spread("area_ratio_before")) << report.dump(2);
  EXPECT_NE(run.err.find(" ms"), std::string::npos) << "the verb reports how long dressing took" << run;
  EXPECT_TRUE(noTemporaries(out));
}

TEST_F(CliTest, DressRefusesMissingBodyFolder) {
  fs::path work = dir("work");
  fs::path body = work / "no-such-body", out = work / "dressed";
  EXPECT_TRUE(refused(runPixelcloth({"dress", "--body", body.string(), "--out", out.string()}),
                      {body.string(), "body folder"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, DressRefusesBrokenBodyFolder) {
  fs::path body = copyOfBody(), out = dir("out") / "dressed";
  writeFile(body / "skeleton.json", "{\"joints\": [ {\"name\": \"root\", ");
  EXPECT_TRUE(refused(runPixelcloth({"dress", "--garment", "necktie", "--body", body.string(), "--out", out.string()}),
                      {(body / "skeleton.json").string(), "JSON"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliTest, DressRefusesUnknownGarment) {
  fs::path out = dir("out") / "dressed";
  EXPECT_TRUE(refused(runPixelcloth({"dress", "--garment", "skirt", "--out", out.string()}), {"skirt"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, DressGivenADatasetFolderPointsAtItsBodyFolder) {
  const fs::path work = dir("work");
  fs::create_directories(work / "data");
  fs::copy(body_, work / "data" / "body", fs::copy_options::recursive);
  EXPECT_TRUE(refused(runPixelcloth({"dress", "--body", (work / "data").string(), "--out", (work / "out").string()}),
                      {"is not a body folder but holds one", (work / "data" / "body").string()}));
  EXPECT_TRUE(filesUnder(work / "out").empty());
}

}  // namespace
}  // namespace pixelcloth::apps
