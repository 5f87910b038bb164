// A garment folder goes wherever a template name goes: written by `pixelcloth garment`, renamed so that no stage can
// find it by name, it is dressed, simulated, imaged, marked, rebuilt, learnt, predicted and evaluated, and the
// dataset carries it to every later verb. The necktie's traits (36-float poses, 64 x 256 images, its own decoder)
// travel with its folder the same way.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "support/cli.h"
#include "support/test_util.h"

namespace {

namespace fs = std::filesystem;
using pixelcloth::testing::CliRun;
using pixelcloth::testing::filesUnder;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::refused;
using pixelcloth::testing::runPixelcloth;

/// `pixelcloth garment KIND --vertices N --out DIR`, then garment.json's name changed to `name`.
void writeRenamedGarment(const std::string& kind, int vertices, const std::string& name, const fs::path& out) {
  const CliRun run = runPixelcloth({"garment", kind, "--vertices", std::to_string(vertices), "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  nlohmann::json json = pixelcloth::core::readJson(out / "garment.json");
  json["name"] = name;
  pixelcloth::core::writeJson(out / "garment.json", json);
}

int verticesOf(const fs::path& obj) { return pixelcloth::core::readMesh(obj).numVertices(); }

}  // namespace

TEST(GarmentFolderCli, ARenamedShirtFolderGoesThroughEveryVerbAndItsDatasetCarriesIt) {
  const fs::path work = freshDir("garment_folder_shirt");
  const fs::path shirt = work / "shirt", data = work / "data";
  // Not the built-in mesh (other vertex count) and not a template's name: only the folder can say what it is.
  writeRenamedGarment("tshirt", 1200, "my_shirt", shirt);
  const int vertices = verticesOf(shirt / "garment.obj");
  ASSERT_LT(vertices, 1500);

  CliRun run = runPixelcloth({"cage", "--garment", shirt.string(), "--out", (work / "cage").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(pixelcloth::core::readJson(work / "cage" / "patches.json").at("patches").size(), 28u);
  run = runPixelcloth({"dress", "--garment", shirt.string(), "--out", (work / "dressed").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(verticesOf(work / "dressed" / "dressed.obj"), vertices);

  run = runPixelcloth({"generate", "--garment", shirt.string(), "--count", "8", "--seed", "3", "--out", data.string(),
                       "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json manifest = pixelcloth::core::readJson(data / "manifest.json");
  EXPECT_EQ(manifest.at("garment"), "my_shirt");
  EXPECT_EQ(manifest.at("vertex_count"), vertices);
  EXPECT_EQ(manifest.at("pose_size"), 90);
  EXPECT_EQ(pixelcloth::core::readJson(data / "garment" / "garment.json").at("name"), "my_shirt");
  run = runPixelcloth({"dataset", "check", data.string()});
  EXPECT_EQ(run.status, 0) << run;

  // Every later verb reads the garment from the dataset.
  run = runPixelcloth({"images", "--dataset", data.string(), "--samples", "0", "--out", (work / "images").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(fs::exists(work / "images" / "cloth_000000.exr"));
  run = runPixelcloth({"markers", "--dataset", data.string(), "--sample", "1", "--pose-out",
                       (work / "pose.json").string(), "--out", (work / "markers.json").string()});
  ASSERT_EQ(run.status, 0) << run;
  run = runPixelcloth({"reconstruct", "--markers", (work / "markers.json").string(), "--pose",
                       (work / "pose.json").string(), "--dressing", data.string(), "--out",
                       (work / "rebuilt.obj").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(verticesOf(work / "rebuilt.obj"), vertices);
  // The markers form also takes the garment folder itself.
  run = runPixelcloth({"reconstruct", "--markers", (work / "markers.json").string(), "--pose",
                       (work / "pose.json").string(), "--garment", shirt.string(), "--out",
                       (work / "rebuilt2.obj").string()});
  ASSERT_EQ(run.status, 0) << run;

  for (const char* model : {"fc", "whole"}) {
    SCOPED_TRACE(model);
    const fs::path out = work / model;
    run = runPixelcloth({"train", "--dataset", data.string(), "--model", model, "--width", "0.0625", "--epochs", "1",
                         "--out", out.string(), "--quiet"});
    ASSERT_EQ(run.status, 0) << run;
    run = runPixelcloth({"predict", "--model", out.string(), "--dataset", data.string(), "--samples", "2", "--out",
                         (work / (std::string(model) + "_predicted")).string()});
    ASSERT_EQ(run.status, 0) << run;
    EXPECT_EQ(verticesOf(work / (std::string(model) + "_predicted") / "sample_000002.obj"), vertices);
    run = runPixelcloth({"evaluate", "--model", out.string(), "--dataset", data.string(), "--out",
                         (work / (std::string(model) + "_evaluated")).string()});
    ASSERT_EQ(run.status, 0) << run;
    const nlohmann::json metrics =
        pixelcloth::core::readJson(work / (std::string(model) + "_evaluated") / "metrics.json");
    EXPECT_GT(metrics.at("vertex_error_cm").get<double>(), 0);
    EXPECT_EQ(metrics.at("patches").size(), 28u);
  }
  run = runPixelcloth({"train", "--dataset", data.string(), "--model", "patch", "--patches", "3", "--width", "0.03125",
                       "--epochs", "1", "--out", (work / "patch").string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(fs::exists(work / "patch" / "patch_03" / "model.tensors"));
}

TEST(GarmentFolderCli, ARenamedNecktieFolderKeepsItsTraits) {
  const fs::path work = freshDir("garment_folder_tie");
  const fs::path tie = work / "tie", data = work / "data";
  writeRenamedGarment("necktie", 400, "bow", tie);
  const nlohmann::json traits = pixelcloth::core::readJson(tie / "garment.json").at("traits");
  EXPECT_EQ(traits.at("pose_joints").size(), 4u);
  EXPECT_EQ(traits.at("image_size"), (std::vector<int>{64, 256}));
  EXPECT_FALSE(traits.at("pinned").empty());

  CliRun run = runPixelcloth({"generate", "--garment", tie.string(), "--count", "3", "--seed", "5", "--out",
                              data.string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(pixelcloth::core::readJson(data / "manifest.json").at("pose_size"), 36);
  run = runPixelcloth({"images", "--dataset", data.string(), "--samples", "0", "--out", (work / "images").string()});
  ASSERT_EQ(run.status, 0) << run;
  run = runPixelcloth({"train", "--dataset", data.string(), "--model", "necktie", "--width", "0.125", "--epochs", "1",
                       "--batch", "2", "--out", (work / "model").string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(refused(runPixelcloth({"train", "--dataset", data.string(), "--model", "whole", "--epochs", "1", "--out",
                                     (work / "whole").string()}),
                      {"whole model does not fit", "bow", "3 x 256 x 64"}));
  EXPECT_TRUE(filesUnder(work / "whole").empty());
}

TEST(GarmentFolderCli, WhatIsNeitherATemplateNorAGarmentFolderIsRefusedByName) {
  const fs::path work = freshDir("garment_folder_bad");
  fs::create_directories(work / "empty");
  pixelcloth::testing::writeFile(work / "file.txt", "not a garment");
  const std::string out = (work / "out").string();
  EXPECT_TRUE(refused(runPixelcloth({"cage", "--garment", "skirt", "--out", out}),
                      {"skirt", "neither a garment template", "tshirt", "necktie"}));
  EXPECT_TRUE(refused(runPixelcloth({"dress", "--garment", (work / "empty").string(), "--out", out}),
                      {(work / "empty").string(), "garment.json"}));
  EXPECT_TRUE(refused(runPixelcloth({"generate", "--garment", (work / "file.txt").string(), "--count", "2", "--out",
                                     out}),
                      {"file.txt", "not a garment folder"}));
  EXPECT_TRUE(filesUnder(work / "out").empty());
  // A dataset carries its garment: naming one beside it is refused rather than silently ignored.
  EXPECT_TRUE(refused(runPixelcloth({"images", "--garment", "tshirt", "--dataset", (work / "empty").string(),
                                     "--samples", "0", "--out", out}),
                      {"--garment", "carries its garment"}));
}

TEST(GarmentFolderCli, TheTShirtComesInSizesAndTheNecktieInOne) {
  const fs::path work = freshDir("garment_sizes");
  CliRun run = runPixelcloth(
      {"garment", "tshirt", "--size", "XL", "--vertices", "800", "--out", (work / "xl").string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json recipe = pixelcloth::core::readJson(work / "xl" / "garment.json").at("template");
  EXPECT_NEAR(recipe.at("options").at("half_width").get<double>(), 1.12 * 0.27, 1e-12);
  EXPECT_NEAR(recipe.at("options").at("neck_side_height").get<double>(), 1.48, 1e-12);
  EXPECT_TRUE(refused(runPixelcloth({"garment", "tshirt", "--size", "XXXL", "--out", (work / "a").string()}),
                      {"XXXL", "XS", "XXL"}));
  EXPECT_TRUE(refused(runPixelcloth({"garment", "necktie", "--grade", "1.1", "--out", (work / "b").string()}),
                      {"necktie", "one size"}));
  EXPECT_TRUE(refused(runPixelcloth({"garment", "tshirt", "--size", "L", "--grade", "1.1", "--out",
                                     (work / "c").string()}),
                      {"--size", "--grade"}));
  EXPECT_TRUE(filesUnder(work / "a").empty() && filesUnder(work / "b").empty() && filesUnder(work / "c").empty());
}
