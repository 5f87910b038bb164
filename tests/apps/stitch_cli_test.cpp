// Seams from the command line on a small simulated T-shirt dataset: evaluate measures every stitch mode on the same
// predictions and fits its PCA filter beside the model, the filter refuses k beyond its rank and another dataset's
// filter is refused, and stitch rebuilds a sample's ground truth from its crops to the image representation's floor.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "pixelcloth/core/mesh_io.h"
#include "support/cli.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace {

namespace fs = std::filesystem;
using pixelcloth::testing::CliRun;
using pixelcloth::testing::filesUnder;
using pixelcloth::testing::readFile;
using pixelcloth::testing::refused;
using pixelcloth::testing::runPixelcloth;

/// 8 simulated shirts (6 train) and a tiny patch model trained on them for one epoch, made once per test process.
struct Shared {
  fs::path root, dataset, other, model;
  bool ok = false;
  CliRun run;
};

const Shared& shared() {
  static const Shared data = [] {
    Shared d;
    d.root = fs::temp_directory_path() / "pixelcloth-tests" / ("stitch-cli." + std::to_string(::getpid()));
    fs::remove_all(d.root);
    fs::create_directories(d.root);
    d.dataset = d.root / "shirts";
    d.other = d.root / "other";
    d.model = d.root / "patch";
    d.run = runPixelcloth({"generate", "--count", "8", "--seed", "3", "--out", d.dataset.string(), "--quiet"});
    if (d.run.status != 0) return d;
    d.run = runPixelcloth({"generate", "--count", "5", "--seed", "4", "--out", d.other.string(), "--quiet"});
    if (d.run.status != 0) return d;
    d.run = runPixelcloth({"train", "--dataset", d.dataset.string(), "--model", "patch", "--width", "0.03125",
                           "--epochs", "1", "--out", d.model.string(), "--quiet"});
    d.ok = d.run.status == 0;
    return d;
  }();
  return data;
}

class StitchCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(shared().ok) << "making the shared dataset and model failed" << shared().run;
    work_ = pixelcloth::testing::freshDir("stitch");
  }
  fs::path work_;
};

TEST_F(StitchCli, EvaluateMeasuresEveryModeOnTheSamePredictions) {
  const fs::path out = work_ / "eval";
  const CliRun run = runPixelcloth({"evaluate", "--model", shared().model.string(), "--dataset",
                                    shared().dataset.string(), "--split", "train", "--stitch",
                                    "mean,feather,pca:4,pca:6", "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json metrics = nlohmann::json::parse(readFile(out / "metrics.json"));
  EXPECT_EQ(metrics["stitch"], "mean");
  ASSERT_EQ(metrics["stitch_modes"].size(), 4u);
  for (const nlohmann::json& m : metrics["stitch_modes"]) {
    SCOPED_TRACE(m["stitch"].get<std::string>());
    const nlohmann::json& seams = m["seams"];
    // The patch networks disagree where their crops overlap: a gap, the same for every mode (it is measured before
    // blending); the jump and the errors are each mode's own.
    EXPECT_GT(seams["gap_cm"]["mean"].get<double>(), 0);
    EXPECT_DOUBLE_EQ(seams["gap_cm"]["mean"].get<double>(), metrics["seams"]["gap_cm"]["mean"].get<double>());
    EXPECT_GE(seams["gap_cm"]["max"].get<double>(), seams["gap_cm"]["mean"].get<double>());
    EXPECT_GT(seams["normal_jump_deg"].get<double>(), 0);
    EXPECT_GT(seams["near_seam_error_cm"].get<double>(), 0);
    EXPECT_GT(seams["interior_error_cm"].get<double>(), 0);
    EXPECT_GT(seams["curves"].size(), 20u);
    EXPECT_EQ(m["samples"], 6);
  }
  // Fewer components change the garment more.
  const double mean = metrics["stitch_modes"][0]["vertex_error_cm"].get<double>();
  EXPECT_NE(metrics["stitch_modes"][2]["vertex_error_cm"].get<double>(), mean);
  // The report: a row per mode, the sweep of k, error maps and the worst seams as pictures.
  const std::string report = readFile(out / "report.md");
  for (const char* row : {"| mean |", "| feather |", "| pca:4 |", "| pca:6 |", "| side_left | seam |", "pca_sweep.png"})
    EXPECT_NE(report.find(row), std::string::npos) << row << "\n" << report;
  for (const char* picture : {"pca_sweep.png", "error_maps_by_mode.png", "worst_seams.png", "error_maps.png"})
    EXPECT_GT(fs::file_size(out / picture), 1000u) << picture;
  // The filter was fitted beside the model and is reused.
  EXPECT_TRUE(fs::exists(shared().model / "pca" / "pca.json"));
  const nlohmann::json pca = nlohmann::json::parse(readFile(shared().model / "pca" / "pca.json"));
  EXPECT_EQ(pca["rank"], 6);
  // k beyond the rank is refused before anything is written.
  EXPECT_TRUE(refused(runPixelcloth({"evaluate", "--model", shared().model.string(), "--dataset",
                                     shared().dataset.string(), "--stitch", "pca:7", "--out",
                                     (work_ / "beyond").string()}),
                      {"pca:7", "rank 6"}));
  EXPECT_FALSE(fs::exists(work_ / "beyond"));
  EXPECT_TRUE(refused(runPixelcloth({"evaluate", "--model", shared().model.string(), "--dataset",
                                     shared().dataset.string(), "--stitch", "median", "--out",
                                     (work_ / "median").string()}),
                      {"median", "feather", "pca:K"}));
}

TEST_F(StitchCli, AFilterOfAnotherDatasetIsRefused) {
  const fs::path filter = work_ / "other_pca";
  CliRun run = runPixelcloth({"pca", "--dataset", shared().other.string(), "--out", filter.string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(fs::exists(filter / "components.npy"));
  EXPECT_TRUE(refused(runPixelcloth({"evaluate", "--model", shared().model.string(), "--dataset",
                                     shared().dataset.string(), "--stitch", "pca:2", "--pca", filter.string(),
                                     "--out", (work_ / "foreign").string()}),
                      {(filter / "pca.json").string(), "fitted on", shared().other.string()}));
  EXPECT_FALSE(fs::exists(work_ / "foreign"));
  // A filter is not fitted into a folder of another kind of run (here the patch model's).
  EXPECT_TRUE(refused(
      runPixelcloth({"pca", "--dataset", shared().dataset.string(), "--out", shared().model.string(), "--quiet"}),
      {"holds", "a PCA filter goes in a folder of its own"}));
  EXPECT_FALSE(fs::exists(shared().model / "pca.json"));
}

TEST_F(StitchCli, GroundTruthCropsStitchBackToTheImagesFloor) {
  const fs::path images = work_ / "images";
  CliRun run = runPixelcloth({"images", "--dataset", shared().dataset.string(), "--samples", "2", "--crops", "--out",
                              images.string()});
  ASSERT_EQ(run.status, 0) << run;
  const fs::path crops = images / "crops_000002";
  EXPECT_TRUE(fs::exists(crops / "patch_00.exr"));
  EXPECT_TRUE(fs::exists(crops / "patch_27.exr"));
  for (const char* mode : {"mean", "feather"}) {
    SCOPED_TRACE(mode);
    const fs::path out = work_ / mode;
    run = runPixelcloth({"stitch", "--patches", crops.string(), "--dataset", shared().dataset.string(), "--sample",
                         "2", "--mode", mode, "--out", out.string()});
    ASSERT_EQ(run.status, 0) << run;
    EXPECT_EQ(filesUnder(out), (std::vector<std::string>{"cloth.exr", "cloth.png", "garment.obj", "stitch.json"}));
    const nlohmann::json report = nlohmann::json::parse(readFile(out / "stitch.json"));
    // Through images, ground truth comes back to the representation's floor, not exactly: rasterising and sampling
    // back is exact to float precision inside a layout, and off by up to a few millimetres where a layout ends (the
    // stitched seams), most at the armpit corner. The exact case, crops as vertex values, is stitch_tests' Seams.
    const nlohmann::json& seams = report["seams"];
    EXPECT_LT(seams["gap_cm"]["mean"].get<double>(), 0.05);
    EXPECT_LT(seams["gap_cm"]["max"].get<double>(), 1.0);
    EXPECT_LT(seams["normal_jump_deg"].get<double>(), 2.0);
    EXPECT_LT(report["vertex_error_cm"].get<double>(), 0.05);
    for (const nlohmann::json& curve : seams["curves"])
      if (curve["kind"] == "split" || curve["kind"] == "centre_line") {
        EXPECT_LT(curve["gap_cm"]["max"].get<double>(), 0.05) << curve["name"];
      }
    EXPECT_EQ(pixelcloth::core::readMesh(out / "garment.obj").numVertices(), pixelcloth::testing::tshirt().mesh.numVertices());
  }
  // A missing crop, and pca without its filter, are refused naming what is missing; nothing is written.
  fs::remove(crops / "patch_13.exr");
  EXPECT_TRUE(refused(runPixelcloth({"stitch", "--patches", crops.string(), "--dataset", shared().dataset.string(),
                                     "--out", (work_ / "missing").string()}),
                      {"patch_13.exr", "28 crops"}));
  EXPECT_TRUE(refused(runPixelcloth({"stitch", "--patches", crops.string(), "--dataset", shared().dataset.string(),
                                     "--mode", "pca:4", "--out", (work_ / "nopca").string()}),
                      {"--pca DIR"}));
  EXPECT_FALSE(fs::exists(work_ / "missing"));
  EXPECT_FALSE(fs::exists(work_ / "nopca"));
}

}  // namespace
