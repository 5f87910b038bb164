// train, predict and evaluate run as programs on a small simulated T-shirt dataset: every model trains and predicts,
// patch decoders trained by separate runs fill one folder, a killed run resumes to the same weights, and bad input
// exits 2 naming the file without writing anything.
#include <gtest/gtest.h>
#include <signal.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <thread>

#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/motion/motion.h"
#include "pixelcloth/motion/sequence.h"
#include "pixelcloth/motion/trajectories.h"
#include "support/cli.h"
#include "support/fixtures.h"
#include "support/python.h"
#include "support/test_util.h"

namespace {

namespace fs = std::filesystem;
using pixelcloth::testing::capture;
using pixelcloth::testing::CliRun;
using pixelcloth::testing::filesUnder;
using pixelcloth::testing::quote;
using pixelcloth::testing::readFile;
using pixelcloth::testing::refused;
using pixelcloth::testing::runPixelcloth;
using pixelcloth::testing::writeFile;

/// 8 simulated shirts (6 train, 1 regularisation, 1 test) and their base folder, made once per test process.
struct SharedData {
  fs::path root, dataset, bases;
  bool ok = false;
  CliRun run;
};

const SharedData& shared() {
  static const SharedData data = [] {
    SharedData d;
    d.root = fs::temp_directory_path() / "pixelcloth-tests" / ("learn-cli." + std::to_string(::getpid()));
    fs::remove_all(d.root);
    fs::create_directories(d.root);
    d.dataset = d.root / "shirts";
    d.bases = d.root / "bases";
    d.run = runPixelcloth({"generate", "--count", "8", "--seed", "3", "--out", d.dataset.string(), "--quiet"});
    if (d.run.status != 0) return d;
    d.run = runPixelcloth({"reconstruct", "--dataset", d.dataset.string(), "--write-base", d.bases.string(), "--quiet"});
    d.ok = d.run.status == 0;
    return d;
  }();
  return data;
}

class LearnCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(shared().ok) << "making the shared dataset failed" << shared().run;
    work_ = pixelcloth::testing::freshDir("work");
  }
  static fs::path dataset() { return shared().dataset; }
  static fs::path bases() { return shared().bases; }
  /// pixelcloth train on the shared dataset with `args` added, expected to succeed.
  static void train(std::initializer_list<std::string> args) {
    std::vector<std::string> words = {"train", "--dataset", dataset().string(), "--quiet"};
    words.insert(words.end(), args.begin(), args.end());
    std::string command = quote(PIXELCLOTH_BINARY);
    for (const std::string& w : words) command += " " + quote(w);
    const CliRun run = capture(command);
    ASSERT_EQ(run.status, 0) << run;
  }
  static nlohmann::json metricsOf(const fs::path& model, const fs::path& out, const std::string& engine = "onednn") {
    const CliRun run = runPixelcloth({"evaluate", "--model", model.string(), "--dataset", dataset().string(), "--out",
                                      out.string(), "--engine", engine});
    EXPECT_EQ(run.status, 0) << run;
    return nlohmann::json::parse(readFile(out / "metrics.json"));
  }
  fs::path work_;
};

TEST_F(LearnCli, EveryModelTrainsPredictsAndIsEvaluated) {
  for (const char* model : {"whole", "fc", "fc-pca"}) {
    SCOPED_TRACE(model);
    const fs::path out = work_ / model;
    train({"--model", model, "--width", "0.0625", "--epochs", "2", "--components", "6", "--out", out.string()});
    const nlohmann::json metrics = metricsOf(out, work_ / (std::string(model) + "_eval"));
    EXPECT_EQ(metrics["split"], "test");
    EXPECT_EQ(metrics["samples"], 1);
    EXPECT_GT(metrics["vertex_error_cm"].get<double>(), 0);
    EXPECT_LT(metrics["vertex_error_cm"].get<double>(), 100);
    EXPECT_EQ(metrics["patches"].size(), 28u);
    EXPECT_TRUE(fs::exists(work_ / (std::string(model) + "_eval") / "error_maps.png"));
    // LibTorch's modules, the reference, measure the same.
    const nlohmann::json reference = metricsOf(out, work_ / (std::string(model) + "_libtorch"), "libtorch");
    EXPECT_NEAR(metrics["vertex_error_cm"].get<double>(), reference["vertex_error_cm"].get<double>(),
                1e-4 * reference["vertex_error_cm"].get<double>());
  }
  // predict, dataset form: an OBJ, EXR and PNG per sample with its posed body, prediction.json listing them, and the
  // error it printed is the evaluation's.
  const fs::path predicted = work_ / "predicted";
  CliRun run = runPixelcloth({"predict", "--model", (work_ / "whole").string(), "--dataset", dataset().string(),
                              "--samples", "0,7", "--out", predicted.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(filesUnder(predicted),
            (std::vector<std::string>{"prediction.json", "sample_000000.exr", "sample_000000.obj", "sample_000000.png",
                                      "sample_000000_body.obj", "sample_000007.exr", "sample_000007.obj",
                                      "sample_000007.png", "sample_000007_body.obj"}));
  EXPECT_EQ(pixelcloth::core::readMesh(predicted / "sample_000000.obj").numVertices(), pixelcloth::testing::tshirt().mesh.numVertices());
  // predict, pose form.
  run = runPixelcloth({"markers", "--dataset", dataset().string(), "--sample", "2", "--pose-out",
                       (work_ / "pose.json").string(), "--out", (work_ / "markers.json").string()});
  ASSERT_EQ(run.status, 0) << run;
  run = runPixelcloth({"predict", "--model", (work_ / "fc").string(), "--pose", (work_ / "pose.json").string(), "--out",
                       (work_ / "posed").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(fs::exists(work_ / "posed" / "garment.obj"));
  EXPECT_EQ(pixelcloth::core::readMesh(work_ / "posed" / "body.obj").numVertices(),
            pixelcloth::core::readMesh(dataset() / "body" / "body.obj").numVertices());
}

TEST_F(LearnCli, PatchDecodersFromTwoRunsMakeOneModelAndResidualOnesStartAtTheBase) {
  const fs::path plain = work_ / "patch", residual = work_ / "residual";
  train({"--model", "patch", "--width", "0.03125", "--epochs", "1", "--patches", "0,1,2,3,4,5,6,7,8,9,10,11,12,13",
         "--out", plain.string()});
  // Half the patches: evaluation refuses, naming the missing ones and the command that trains them.
  EXPECT_TRUE(refused(runPixelcloth({"evaluate", "--model", plain.string(), "--dataset", dataset().string(), "--out",
                                     (work_ / "half").string()}),
                      {"missing: 14,15", "--patches 14,15"}));
  EXPECT_FALSE(fs::exists(work_ / "half"));
  train({"--model", "patch", "--width", "0.03125", "--epochs", "1", "--patches",
         "14,15,16,17,18,19,20,21,22,23,24,25,26,27", "--out", plain.string()});
  EXPECT_GT(metricsOf(plain, work_ / "plain_eval")["vertex_error_cm"].get<double>(), 0);

  // The folder now holds a patch model of width 0.03125: a run of other settings, another kind of model or a GAN
  // blender would leave it mixed, and is refused before anything is written; so is a dataset folder.
  const std::string decoder = readFile(plain / "patch_05" / "model.json");
  auto trainInto = [&](std::initializer_list<std::string> args) {
    std::string command = quote(PIXELCLOTH_BINARY) + " train --epochs 1 --dataset " + quote(dataset().string());
    for (const std::string& word : args) command += " " + quote(word);
    return capture(command);
  };
  EXPECT_TRUE(refused(trainInto({"--model", "patch", "--patches", "5", "--width", "0.0625", "--out", plain.string()}),
                      {"/model.json: the folder holds a run with width 0.03125, this one's is 0.0625"}));
  EXPECT_TRUE(refused(trainInto({"--model", "fc", "--out", plain.string()}), {"holds a patch model", "the fc model"}));
  EXPECT_TRUE(refused(trainInto({"--model", "gan", "--patch-model", plain.string(), "--out", plain.string()}),
                      {"holds a patch model", "a GAN blender"}));
  EXPECT_TRUE(refused(trainInto({"--model", "patch", "--patches", "5", "--out", dataset().string()}),
                      {"holds a dataset (manifest.json)"}));
  // The same rule keeps an evaluation or a prediction out of them.
  EXPECT_TRUE(refused(
      runPixelcloth({"evaluate", "--model", plain.string(), "--dataset", dataset().string(), "--out", plain.string()}),
      {"holds a patch model", "an evaluation goes in a folder of its own"}));
  EXPECT_TRUE(refused(runPixelcloth({"predict", "--model", plain.string(), "--dataset", dataset().string(), "--samples",
                                     "7", "--out", dataset().string()}),
                      {"holds a dataset (manifest.json); a prediction"}));
  EXPECT_EQ(readFile(plain / "patch_05" / "model.json"), decoder);
  EXPECT_FALSE(fs::exists(plain / "model.json"));
  EXPECT_FALSE(fs::exists(dataset() / "patch_05"));

  // Residual mode: an untrained model predicts the base, so one epoch is already near the markers' garment.
  train({"--model", "patch", "--width", "0.03125", "--epochs", "1", "--residual", bases().string(), "--out",
         residual.string()});
  const nlohmann::json metrics = metricsOf(residual, work_ / "residual_eval");
  const double base = metrics["base_vertex_error_cm"].get<double>(), learned = metrics["vertex_error_cm"].get<double>();
  std::cout << "[residual patches, 1 epoch, 6 train samples] test error " << learned << " cm, markers alone " << base
            << " cm\n";
  EXPECT_GT(base, 0.1);
  EXPECT_LT(learned, 2 * base);

  // predict with markers: the residual model rebuilds the base from them.
  CliRun run = runPixelcloth({"markers", "--dataset", dataset().string(), "--sample", "7", "--pose-out",
                              (work_ / "pose.json").string(), "--out", (work_ / "markers.json").string()});
  ASSERT_EQ(run.status, 0) << run;
  run = runPixelcloth({"predict", "--model", residual.string(), "--pose", (work_ / "pose.json").string(), "--markers",
                       (work_ / "markers.json").string(), "--out", (work_ / "from_markers").string()});
  ASSERT_EQ(run.status, 0) << run;
  // The same sample from the dataset form (its base from the base folder): the same garment.
  run = runPixelcloth({"predict", "--model", residual.string(), "--dataset", dataset().string(), "--samples", "7",
                       "--out", (work_ / "from_dataset").string()});
  ASSERT_EQ(run.status, 0) << run;
  const Eigen::MatrixX3d a = pixelcloth::core::readMesh(work_ / "from_markers" / "garment.obj").V,
                         b = pixelcloth::core::readMesh(work_ / "from_dataset" / "sample_000007.obj").V;
  EXPECT_LT((a - b).rowwise().norm().maxCoeff(), 1e-4);
  // Without markers it cannot.
  EXPECT_TRUE(refused(runPixelcloth({"predict", "--model", residual.string(), "--pose", (work_ / "pose.json").string(),
                                     "--out", (work_ / "no_markers").string()}),
                      {"residual model", "--markers"}));
  EXPECT_FALSE(fs::exists(work_ / "no_markers"));
}

TEST_F(LearnCli, AKilledRunResumesToTheWeightsOfAnUninterruptedOne) {
  const fs::path whole = work_ / "uninterrupted", killed = work_ / "killed";
  const std::vector<std::string> args = {"--model", "fc", "--width", "0.25", "--epochs", "150", "--batch", "2"};
  auto command = [&](const fs::path& out) {
    std::string c = quote(PIXELCLOTH_BINARY) + " train --dataset " + quote(dataset().string()) + " --quiet";
    for (const std::string& a : args) c += " " + quote(a);
    return c + " --out " + quote(out.string());
  };
  ASSERT_EQ(capture(command(whole)).status, 0);
  // Start the same run in the background and kill -9 it once a few epochs are in its checkpoint.
  const CliRun started = capture(command(killed) + " >/dev/null 2>&1 & echo $!");
  const int pid = std::stoi(started.out);
  const auto start = std::chrono::steady_clock::now();
  auto epochsLogged = [&] {
    const std::string log = readFile(killed / "log.csv");
    return static_cast<int>(std::count(log.begin(), log.end(), '\n')) - 1;
  };
  while (epochsLogged() < 5 && std::chrono::steady_clock::now() - start < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  capture("while kill -0 " + std::to_string(pid) + " 2>/dev/null; do sleep 0.05; done");
  const int done = epochsLogged();
  std::cout << "[fc] killed after " << done << " of 150 epochs\n";
  ASSERT_LT(done, 150) << "the run ended before it was killed; nothing was tested";
  ASSERT_EQ(capture(command(killed)).status, 0);
  EXPECT_EQ(readFile(whole / "model.tensors"), readFile(killed / "model.tensors"));
  EXPECT_EQ(nlohmann::json::parse(readFile(whole / "model.json"))["epoch"],
            nlohmann::json::parse(readFile(killed / "model.json"))["epoch"]);
}

TEST_F(LearnCli, BadInputIsRefusedNamingTheFile) {
  const fs::path model = work_ / "model";
  train({"--model", "fc", "--width", "0.125", "--epochs", "1", "--out", model.string()});
  // A pose of the wrong size.
  writeFile(work_ / "short_pose.json", R"({"pose": [1, 0, 0, 0, 1, 0, 0, 0, 1]})");
  EXPECT_TRUE(refused(runPixelcloth({"predict", "--model", model.string(), "--pose",
                                     (work_ / "short_pose.json").string(), "--out", (work_ / "a").string()}),
                      {"short_pose.json"}));
  EXPECT_FALSE(fs::exists(work_ / "a"));
  // A truncated checkpoint.
  const fs::path broken = work_ / "broken";
  fs::copy(model, broken);
  const std::string weights = readFile(model / "model.tensors");
  writeFile(broken / "model.tensors", weights.substr(0, weights.size() / 2));
  EXPECT_TRUE(refused(runPixelcloth({"evaluate", "--model", broken.string(), "--dataset", dataset().string(), "--out",
                                     (work_ / "b").string()}),
                      {"model.tensors", "truncated"}));
  EXPECT_FALSE(fs::exists(work_ / "b"));
  // An engine that does not exist; a negative number of networks at once.
  EXPECT_TRUE(refused(runPixelcloth({"evaluate", "--model", model.string(), "--dataset", dataset().string(), "--out",
                                     (work_ / "e").string(), "--engine", "mkl"}),
                      {"--engine", "mkl"}));
  EXPECT_FALSE(fs::exists(work_ / "e"));
  EXPECT_TRUE(refused(runPixelcloth({"train", "--dataset", dataset().string(), "--model", "patch", "--patches", "0",
                                     "--networks-at-once", "-1", "--out", (work_ / "n").string()}),
                      {"networks at once"}));
  EXPECT_FALSE(fs::exists(work_ / "n"));
  // A model trained on another garment's dataset.
  const CliRun tie = runPixelcloth({"generate", "--garment", "necktie", "--count", "3", "--seed", "5", "--out",
                                    (work_ / "tie").string(), "--quiet"});
  ASSERT_EQ(tie.status, 0) << tie;
  EXPECT_TRUE(refused(runPixelcloth({"evaluate", "--model", model.string(), "--dataset", (work_ / "tie").string(),
                                     "--out", (work_ / "c").string()}),
                      {"model.json", "tshirt", "necktie"}));
  EXPECT_FALSE(fs::exists(work_ / "c"));
  // A base folder of another dataset.
  CliRun run = runPixelcloth(
      {"reconstruct", "--dataset", (work_ / "tie").string(), "--write-base", (work_ / "tie_bases").string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(refused(runPixelcloth({"train", "--dataset", dataset().string(), "--model", "fc", "--residual",
                                     (work_ / "tie_bases").string(), "--out", (work_ / "d").string()}),
                      {"tie_bases", "manifest"}));
  EXPECT_FALSE(fs::exists(work_ / "d"));
  // --patches for a model that has none, and a patch that does not exist.
  EXPECT_TRUE(refused(runPixelcloth({"train", "--dataset", dataset().string(), "--model", "whole", "--patches", "3",
                                     "--out", (work_ / "e").string()}),
                      {"--patches"}));
  EXPECT_TRUE(refused(runPixelcloth({"train", "--dataset", dataset().string(), "--model", "patch", "--patches", "3,x",
                                     "--out", (work_ / "e").string()}),
                      {"--patches"}));
  EXPECT_FALSE(fs::exists(work_ / "e"));
  // Another run's settings in the output folder.
  EXPECT_TRUE(refused(runPixelcloth({"train", "--dataset", dataset().string(), "--model", "fc", "--width", "0.125",
                                     "--epochs", "2", "--lr", "0.01", "--out", model.string()}),
                      {"checkpoint.tensors", "learning_rate"}));
}

}  // namespace

// predict --motion: a clip imported by motion import, every frame predicted by the patch model; the PC2 caches read
// back by numpy and against the OBJ frames; the temporal measures and pictures written; a damaged motion refused.
TEST_F(LearnCli, AMotionClipBecomesAnAnimatedGarment) {
  const fs::path model = work_ / "patch", motion = work_ / "motion", out = work_ / "animated";
  train({"--model", "patch", "--width", "0.03125", "--epochs", "1", "--out", model.string()});
  const CliRun imported =
      runPixelcloth({"--clamp-to-limits", "motion", "import",
                     pixelcloth::testing::asset("motion/cmu_style.bvh").string(), "--out", motion.string()});
  ASSERT_EQ(imported.status, 0) << imported;
  const CliRun run =
      runPixelcloth({"predict", "--model", model.string(), "--motion", motion.string(), "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_NE(run.out.find("4 frames at 120"), std::string::npos) << run;
  for (const char* name : {"animation.glb", "frames/garment_0000.obj", "frames/garment_0003.obj", "garment.obj",
                           "body.obj", "garment.pc2", "body.pc2", "strip.png", "temporal.png", "metrics.json"})
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  EXPECT_FALSE(fs::exists(out / "frames" / "garment_0004.obj"));
  const nlohmann::json metrics = nlohmann::json::parse(readFile(out / "metrics.json"));
  EXPECT_EQ(metrics["frames"], 4);
  EXPECT_GT(metrics["garment_jitter_cm"]["mean"].get<double>(), 0);
  EXPECT_GT(metrics["body_jitter_cm"]["mean"].get<double>(), 0);
  EXPECT_TRUE(metrics["garment_jitter_cm"]["per_frame"][0].is_null());  // no neighbours before the first frame
  EXPECT_EQ(metrics["inside_body"]["vertices_per_frame"].size(), 4u);
  EXPECT_GT(metrics["seam_gap_cm"]["mean"].get<double>(), 0);  // 28 decoders, one epoch: they disagree
  EXPECT_EQ(metrics["seam_gap_cm"]["per_frame"].size(), 4u);

  // numpy reads the caches as Blender's Mesh Cache modifier would: header, then frames x points x 3 float32.
  const pixelcloth::core::Mesh frame2 = pixelcloth::core::readMesh(out / "frames" / "garment_0002.obj");
  if (!pixelcloth::testing::numpyPython().empty()) {
    const std::string checked = pixelcloth::testing::runPython(
        "import sys, numpy as np\n"
        "def pc2(path):\n"
        "    raw = open(path, 'rb').read()\n"
        "    assert raw[:12] == b'POINTCACHE2\\0', raw[:12]\n"
        "    version, points = np.frombuffer(raw[12:20], '<i4')\n"
        "    start, rate = np.frombuffer(raw[20:28], '<f4')\n"
        "    samples = np.frombuffer(raw[28:32], '<i4')[0]\n"
        "    assert version == 1 and rate == 1 and start == 0\n"
        "    return np.frombuffer(raw[32:], '<f4').reshape(samples, points, 3)\n"
        "g = pc2(sys.argv[1] + '/garment.pc2'); b = pc2(sys.argv[1] + '/body.pc2')\n"
        "v = np.array([[float(x) for x in l.split()[1:4]] for l in open(sys.argv[1] + '/frames/garment_0002.obj')\n"
        "              if l.startswith('v ')])\n"
        "assert g.shape == (4, len(v), 3), g.shape\n"
        "assert np.abs(g[2] - v).max() < 1e-5, np.abs(g[2] - v).max()\n"
        "assert b.shape[0] == 4 and np.isfinite(b).all()\n"
        "print('ok', g.shape[1])\n",
        out);
    EXPECT_EQ(checked, "ok " + std::to_string(frame2.numVertices()) + "\n");
  }

  // A motion whose poses.npy lost its tail is refused naming it, and nothing is written.
  const std::string poses = readFile(motion / "poses.npy");
  writeFile(motion / "poses.npy", poses.substr(0, poses.size() - 100));
  EXPECT_TRUE(refused(runPixelcloth({"predict", "--model", model.string(), "--motion", motion.string(), "--out",
                                     (work_ / "none").string()}),
                      {"poses.npy"}));
  EXPECT_FALSE(fs::exists(work_ / "none"));
}

// reconstruct --markers-sequence: four of the dataset's shirts as the frames of a capture whose root turns and walks,
// their markers taken in its world by markers --pc2 with a fifth of the curve markers lost in each frame; rebuilt frame
// by frame by the spline alone and refined by a residual model, the garments come back near the shirts they were
// taken from. A frame that loses a curve's end, and trajectories of another length, are refused.
TEST_F(LearnCli, MarkerTrajectoriesAreRebuiltFrameByFrame) {
  namespace pm = pixelcloth::motion;
  const pixelcloth::data::Dataset data = pixelcloth::data::openDataset(dataset());
  const pixelcloth::body::Body body = pixelcloth::data::loadDatasetBody(dataset());
  const Eigen::Vector3d root = body.skeleton.positions.row(body.skeleton.index("root")).transpose();
  pm::Motion motion;
  motion.fps = 24;
  motion.source = "four shirts";
  motion.rootTranslations.resize(4, 3);
  std::vector<Eigen::MatrixX3d> shirts;
  for (int f = 0; f < 4; ++f) {
    motion.poses.push_back(pixelcloth::body::Pose::fromLeading(data.pose(f)));
    motion.rootRotations.push_back(Eigen::AngleAxisd(0.3 * f, Eigen::Vector3d::UnitY()).toRotationMatrix());
    motion.rootTranslations.row(f) << 0.05 * f, 0, 0.2 * f;
    shirts.push_back(data.positionsOf(f).cast<double>());
  }
  const fs::path motionDir = work_ / "motion", out = work_ / "rebuilt", refined = work_ / "refined";
  pm::writeMotion(motionDir, motion);
  const std::vector<Eigen::MatrixX3d> world = pm::withRootMotion(shirts, motion, root);
  pm::writePc2(work_ / "shirts.pc2", world);
  const fs::path markers = work_ / "markers.json", trajectories = work_ / "trajectories.npy";
  CliRun run = runPixelcloth({"markers", "--pc2", (work_ / "shirts.pc2").string(), "--trajectories",
                              trajectories.string(), "--dropout", "0.2", "--seed", "3", "--out", markers.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json definition = nlohmann::json::parse(readFile(markers));
  const pm::MarkerTrajectories read =
      pm::readMarkerTrajectories(trajectories, static_cast<int>(definition["markers"].size()), "markers.json");
  int lost = 0;
  for (const Eigen::MatrixX3d& frame : read.frames) lost += static_cast<int>(frame.col(0).array().isNaN().count());
  EXPECT_GT(lost, 4);

  auto errorCm = [&](const fs::path& folder) {
    const std::vector<Eigen::MatrixX3f> garments = pm::readPc2(folder / "garment.pc2");
    EXPECT_EQ(garments.size(), 4u);
    double error = 0;
    for (int f = 0; f < 4 && f < static_cast<int>(garments.size()); ++f)
      error += 100 * (garments[f].cast<double>() - world[f]).rowwise().norm().mean() / 4;
    return error;
  };
  run = runPixelcloth({"reconstruct", "--markers-sequence", trajectories.string(), "--markers", markers.string(),
                       "--motion", motionDir.string(), "--dressing", dataset().string(), "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  for (const char* name : {"animation.glb", "frames/garment_0003.obj", "garment.pc2", "body.pc2", "strip.png",
                           "temporal.png", "metrics.json"})
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  const double spline = errorCm(out);
  const nlohmann::json metrics = nlohmann::json::parse(readFile(out / "metrics.json"));
  EXPECT_EQ(metrics["frames"], 4);
  EXPECT_TRUE(metrics["seam_gap_cm"].is_null());  // one garment, no patch networks
  EXPECT_EQ(metrics["method"], "spline");

  const fs::path residual = work_ / "residual";
  train({"--model", "patch", "--width", "0.03125", "--epochs", "1", "--residual", bases().string(), "--out",
         residual.string()});
  run = runPixelcloth({"reconstruct", "--markers-sequence", trajectories.string(), "--markers", markers.string(),
                       "--motion", motionDir.string(), "--model", residual.string(), "--out", refined.string()});
  ASSERT_EQ(run.status, 0) << run;
  const double learned = errorCm(refined);
  const nlohmann::json refinedMetrics = nlohmann::json::parse(readFile(refined / "metrics.json"));
  EXPECT_GE(refinedMetrics["seam_gap_cm"]["mean"].get<double>(), 0);
  std::cout << "[4 frames, 20% of the curve markers lost] spline " << spline << " cm, residual patches (1 epoch) "
            << learned << " cm" << std::endl;
  EXPECT_LT(spline, 1.5);
  EXPECT_LT(learned, 1.5);

  // Frame 2 loses the marker at the end of a seam, then the trajectories lose a frame.
  pm::MarkerTrajectories damaged = read;
  int junction = 0;  // where the side seam ends at the hem
  while (definition["markers"][junction]["name"] != "hem/side_left") ++junction;
  damaged.frames[1].row(junction).setConstant(std::nan(""));
  pm::writeMarkerTrajectories(work_ / "lost_end.npy", damaged);
  EXPECT_TRUE(
      refused(runPixelcloth({"reconstruct", "--markers-sequence", (work_ / "lost_end.npy").string(), "--markers",
                             markers.string(), "--motion", motionDir.string(), "--dressing", dataset().string(),
                             "--out", (work_ / "none").string()}),
              {"lost_end.npy: frame 2", "its end", definition["markers"][junction]["name"].get<std::string>()}));
  damaged = read;
  damaged.frames.pop_back();
  pm::writeMarkerTrajectories(work_ / "short.npy", damaged);
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--markers-sequence", (work_ / "short.npy").string(), "--markers",
                                     markers.string(), "--motion", motionDir.string(), "--dressing", dataset().string(),
                                     "--out", (work_ / "none").string()}),
                      {"short.npy", "3 frames, but the motion has 4"}));
  EXPECT_FALSE(fs::exists(work_ / "none"));
}
