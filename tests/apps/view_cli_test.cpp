// pixelcloth view: each kind of output folder becomes a page that headless Chromium opens. The page reports what it
// drew (meshes and their vertex counts, frames, markers, cage curves, pixels drawn, console errors) in a status
// element, read here from the DOM and compared with the files; a screenshot must show more than the background.
// A machine without Chromium fails these tests, saying so: ./scripts/setup installs it.
#include "cli_fixtures.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/motion/motion.h"

namespace pixelcloth::apps {
namespace {

fs::path chromium() {
  const char* env = std::getenv("PIXELCLOTH_CHROMIUM");
  return env && *env ? fs::path(env) : fs::path("/usr/bin/chromium");
}

std::string chromiumCommand(const fs::path& profile) {
  // SwiftShader is Chromium's own software WebGL: no GPU and no display needed. Each run has its own profile, so that
  // tests running at once do not wait on one profile's lock.
  return "timeout 120 " + quote(chromium().string()) +
         " --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --no-first-run"
         " --user-data-dir=" +
         quote(profile.string()) + " --virtual-time-budget=60000";
}

struct PageStatus {
  nlohmann::json status;
  CliRun run;
};

/// Opens SITE/index.html?check=all, which loads every scene in turn, and returns the status it reports.
PageStatus checkAllScenes(const fs::path& site, const fs::path& work) {
  PageStatus page;
  if (!fs::exists(chromium())) {
    ADD_FAILURE() << chromium() << " not found: the viewer tests need Debian's chromium (./scripts/setup installs it; "
                  << "PIXELCLOTH_CHROMIUM names another)";
    return page;
  }
  page.run = capture(chromiumCommand(work / "profile-dom") + " --dump-dom " +
                     quote("file://" + fs::absolute(site / "index.html").string() + "?check=all"));
  const std::string open = "<pre id=\"pixelcloth-status\">";
  const size_t begin = page.run.out.find(open), end = page.run.out.find("</pre>", begin);
  if (page.run.status != 0 || begin == std::string::npos || end == std::string::npos) {
    ADD_FAILURE() << "Chromium did not start or did not show the page" << page.run;
    return page;
  }
  std::string text = page.run.out.substr(begin + open.size(), end - begin - open.size());
  for (const auto& [entity, character] :
       std::vector<std::pair<std::string, std::string>>{{"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&amp;", "&"}})
    for (size_t at = text.find(entity); at != std::string::npos; at = text.find(entity, at + 1))
      text.replace(at, entity.size(), character);
  page.status = nlohmann::json::parse(text, nullptr, false);
  if (page.status.is_discarded()) ADD_FAILURE() << "the page's status is not JSON: " << text;
  return page;
}

/// What every page must report: every scene loaded and drawn, WebGL up, no error on the console.
void expectEveryScene(const PageStatus& page, size_t scenes) {
  const nlohmann::json& status = page.status;
  ASSERT_TRUE(status.is_object()) << page.run;
  EXPECT_TRUE(status.value("webgl", false)) << status.dump(1);
  EXPECT_TRUE(status.value("done", false)) << status.dump(1);
  EXPECT_EQ(status["errors"].size(), 0u) << status["errors"].dump(1);
  ASSERT_EQ(status["scenes"].size(), scenes) << status.dump(1);
  for (const nlohmann::json& scene : status["scenes"]) {
    SCOPED_TRACE(scene["name"].get<std::string>());
    // Not a blank canvas: the garment and body cover a good part of it.
    EXPECT_GT(scene["drawn_pixels"].get<double>(), 0.02 * scene["canvas_pixels"].get<double>()) << scene.dump();
  }
}

/// A screenshot of scene `scene`: a PNG with more than the page's white and grey in its view.
void expectScreenshot(const fs::path& site, const fs::path& work, int scene) {
  if (!fs::exists(chromium())) return;  // checkAllScenes said so
  const fs::path png = work / ("screenshot_" + std::to_string(scene) + ".png");
  const CliRun run =
      capture(chromiumCommand(work / "profile-shot") + " --window-size=1200,800 --screenshot=" + quote(png.string()) +
              " " + quote("file://" + fs::absolute(site / "index.html").string() + "?scene=" + std::to_string(scene)));
  ASSERT_TRUE(isPng(png)) << run;
  const core::RgbImage shot = core::readPng(png);
  long coloured = 0;
  for (int y = 0; y < shot.height; ++y)
    for (int x = 320; x < shot.width; ++x) {  // right of the side panel
      const std::uint8_t* p = shot.at(x, y);
      const int spread = std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]});
      if (spread > 30) ++coloured;  // the garment's colours; the body and the background are grey or white
    }
  EXPECT_GT(coloured, 2000) << png << ": the view shows no garment";
}

int sceneCount(const fs::path& site) {
  const std::string text = readFile(site / "site.js");
  return static_cast<int>(
      nlohmann::json::parse(text.substr(text.find('=') + 1, text.rfind(';') - text.find('=') - 1))["scenes"].size());
}

/// Necktie outputs of every kind, made by the real verbs on a 10-sample dataset simulated on the mannequin.
class ViewCli : public CliTest {
 protected:
  void SetUp() override {
    work_ = dir("work");
    const CliRun run = runPixelcloth(
        {"generate", "--garment", "necktie", "--count", "10", "--seed", "2", "--out", dataset().string(), "--quiet"});
    ASSERT_EQ(run.status, 0) << run;
    tieVertices_ = core::readMesh(dataset() / "garment" / "garment.obj").numVertices();
    bodyVertices_ = core::readMesh(dataset() / "body" / "body.obj").numVertices();
  }
  fs::path dataset() const { return work_ / "tie"; }
  fs::path model() {
    const fs::path out = work_ / "model";
    if (!fs::exists(out)) {
      const CliRun run = runPixelcloth({"train", "--dataset", dataset().string(), "--model", "necktie", "--width",
                                        "0.0625", "--epochs", "1", "--out", out.string(), "--quiet"});
      EXPECT_EQ(run.status, 0) << run;
    }
    return out;
  }
  /// pixelcloth view FOLDER, then the page in Chromium: every scene drawn, the status returned.
  nlohmann::json viewed(const fs::path& folder) {
    const fs::path site = work_ / (folder.filename().string() + "_site");
    const CliRun run = runPixelcloth({"view", folder.string(), "--out", site.string()});
    EXPECT_EQ(run.status, 0) << run;
    EXPECT_TRUE(noTemporaries(site));
    for (const char* file : {"index.html", "viewer.js", "site.js", "three/three.min.js", "three/GLTFLoader.js",
                             "three/OrbitControls.js", "scenes/000.glb", "scenes/000.glb.js"})
      EXPECT_TRUE(fs::is_regular_file(site / file)) << file;
    const PageStatus page = checkAllScenes(site, work_);
    expectEveryScene(page, static_cast<size_t>(sceneCount(site)));
    expectScreenshot(site, work_, 0);
    return page.status;
  }
  fs::path work_;
  int tieVertices_ = 0, bodyVertices_ = 0;
};

TEST_F(ViewCli, ADatasetShowsItsSamplesOnTheirBodies) {
  const nlohmann::json status = viewed(dataset());
  ASSERT_EQ(status["scenes"].size(), 10u);
  for (const nlohmann::json& scene : status["scenes"]) {
    EXPECT_EQ(scene["meshes"]["simulated"], tieVertices_);
    EXPECT_EQ(scene["meshes"]["body"], bodyVertices_);
    EXPECT_EQ(scene["frames"], 1);
    EXPECT_GT(scene["curve_segments"].get<int>(), 10) << "the tie's cage curves";
  }
}

TEST_F(ViewCli, AnEvaluationShowsEachPredictionAgainstGroundTruth) {
  const fs::path out = work_ / "eval";
  const CliRun run = runPixelcloth({"evaluate", "--model", model().string(), "--dataset", dataset().string(), "--split",
                                    "train", "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json metrics = nlohmann::json::parse(readFile(out / "metrics.json"));
  const nlohmann::json status = viewed(out);
  ASSERT_EQ(status["scenes"].size(), metrics["rows"].size());
  for (const nlohmann::json& scene : status["scenes"]) {
    EXPECT_EQ(scene["meshes"]["ground truth"], tieVertices_);
    EXPECT_EQ(scene["meshes"]["prediction (mean)"], tieVertices_) << scene.dump();
  }
}

TEST_F(ViewCli, APredictionShowsEachSampleWithItsBody) {
  const fs::path out = work_ / "pred";
  const CliRun run = runPixelcloth({"predict", "--model", model().string(), "--dataset", dataset().string(),
                                    "--samples", "1,4", "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(fs::is_regular_file(out / "sample_000004_body.obj"));
  const nlohmann::json status = viewed(out);
  ASSERT_EQ(status["scenes"].size(), 2u);
  EXPECT_EQ(status["scenes"][1]["name"], "sample_000004.obj");
  EXPECT_EQ(status["scenes"][1]["meshes"]["prediction"], tieVertices_);
  EXPECT_EQ(status["scenes"][1]["meshes"]["ground truth"], tieVertices_);
  EXPECT_EQ(status["scenes"][1]["meshes"]["body"], bodyVertices_);
}

TEST_F(ViewCli, AReconstructionShowsEveryMethodAndTheMarkers) {
  const fs::path out = work_ / "rec";
  const CliRun run = runPixelcloth({"reconstruct", "--dataset", dataset().string(), "--out", out.string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json metrics = nlohmann::json::parse(readFile(out / "metrics.json"));
  const nlohmann::json status = viewed(out);
  ASSERT_GE(status["scenes"].size(), 1u);
  const nlohmann::json& scene = status["scenes"][0];
  for (const char* method : {"linear", "catmull_rom", "spline", "spline_anisotropic", "ground truth"})
    EXPECT_EQ(scene["meshes"][method], tieVertices_) << method;
  EXPECT_EQ(scene["markers"], metrics["markers"]);
}

/// predict --motion and reconstruct --markers-sequence on the CMU-style clip, its arms held still (the necktie's
/// networks see the four torso joints only).
TEST_F(ViewCli, SequencesPlayEveryFrameWithTheirMarkers) {
  const fs::path clip = work_ / "clip", seq = work_ / "seq", rebuilt = work_ / "rebuilt";
  const CliRun imported =
      runPixelcloth({"--clamp-to-limits", "motion", "import",
                     pixelcloth::testing::asset("motion/cmu_style.bvh").string(), "--out", clip.string()});
  ASSERT_EQ(imported.status, 0) << imported;
  motion::Motion torso = motion::readMotion(clip);
  for (body::Pose& pose : torso.poses)
    for (size_t j = 4; j < pose.rotations.size(); ++j) pose.rotations[j] = Eigen::Matrix3d::Identity();
  motion::writeMotion(clip, torso);
  CliRun run =
      runPixelcloth({"predict", "--model", model().string(), "--motion", clip.string(), "--out", seq.string()});
  ASSERT_EQ(run.status, 0) << run;
  run = runPixelcloth({"markers", "--pc2", (seq / "garment.pc2").string(), "--trajectories", (work_ / "T.npy").string(),
                       "--garment", "necktie", "--dropout", "0.2", "--out", (work_ / "M.json").string()});
  ASSERT_EQ(run.status, 0) << run;
  run = runPixelcloth({"reconstruct", "--markers-sequence", (work_ / "T.npy").string(), "--markers",
                       (work_ / "M.json").string(), "--motion", clip.string(), "--out", rebuilt.string()});
  ASSERT_EQ(run.status, 0) << run;
  for (const fs::path& folder : {seq, rebuilt}) {
    SCOPED_TRACE(folder.filename().string());
    const nlohmann::json status = viewed(folder);
    // The captured markers of frame 1, where they are.
    if (folder == rebuilt) {
      EXPECT_GT(status["scenes"][0]["markers"].get<int>(), 0);
    }
    ASSERT_EQ(status["scenes"].size(), 1u);
    const nlohmann::json& scene = status["scenes"][0];
    EXPECT_EQ(scene["frames"], 4);
    EXPECT_EQ(scene["meshes"]["body"], bodyVertices_);
    EXPECT_GT(scene["last_frame_moved_m"].get<double>(), 1e-3) << "the frames are the clip's, not frame 0 again";
    EXPECT_GT(scene["last_frame_drawn_pixels"].get<double>(), 0.02 * scene["canvas_pixels"].get<double>());
    EXPECT_GT(scene["curve_segments"].get<int>(), 10) << "the cage of the model's garment";
  }
}

/// A folder holding outputs (the demo's report is one): every viewable folder under it, as a group of scenes.
TEST_F(ViewCli, AFolderOfOutputsShowsEachAsAGroup) {
  const CliRun run =
      runPixelcloth({"reconstruct", "--dataset", dataset().string(), "--out", (work_ / "rec").string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json status = viewed(work_);
  // Four of the dataset's samples (a report shows at most four of each) and the reconstruction's one.
  EXPECT_EQ(status["scenes"].size(), 5u) << status.dump(1);
}

TEST_F(ViewCli, WhatCannotBeShownIsRefusedNamingIt) {
  const fs::path empty = dir("empty");
  EXPECT_TRUE(refused(runPixelcloth({"view", empty.string(), "--out", (work_ / "site").string()}),
                      {"holds no output pixelcloth can show"}));
  EXPECT_FALSE(fs::exists(work_ / "site"));
  EXPECT_TRUE(refused(runPixelcloth({"view", (work_ / "missing").string()}), {"is not a folder"}));
  // An evaluation whose predictions do not match its samples.
  const fs::path out = work_ / "eval";
  ASSERT_EQ(runPixelcloth({"evaluate", "--model", model().string(), "--dataset", dataset().string(), "--split", "train",
                           "--out", out.string()})
                .status,
            0);
  core::writeNpy(out / "predictions.npy", std::vector<float>(9, 0.0f), {1, 3, 3});
  EXPECT_TRUE(refused(runPixelcloth({"view", out.string(), "--out", (work_ / "site").string()}),
                      {"predictions.npy", "expected"}));
  EXPECT_FALSE(fs::exists(work_ / "site"));
}

}  // namespace
}  // namespace pixelcloth::apps
