// Runs the real `pixelcloth` executable: each verb's outputs, and bad input refused with exit code 2, a message
// naming the file or option and what was expected, and no half-written files.
#include "support/cli.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "pixelcloth/core/exr_io.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/data/base_set.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/garment/garment.h"
#include "support/test_util.h"

namespace pixelcloth::apps {
namespace {

namespace fs = std::filesystem;
using pixelcloth::testing::capture;
using pixelcloth::testing::CliRun;
using pixelcloth::testing::filesUnder;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::quote;
using pixelcloth::testing::readFile;
using pixelcloth::testing::refused;
using pixelcloth::testing::runPixelcloth;
using pixelcloth::testing::writeFile;

/// The 10 posable joints, as `pixelcloth body --joints` requires them.
const std::vector<std::string> kPoseJointNames = {"lower_back", "spine",     "spine1",     "neck",  "l_shoulder",
                                                  "l_arm",      "l_forearm", "r_shoulder", "r_arm", "r_forearm"};

// ---------------------------------------------------------------------------------------------------------------------
// Running commands

// ---------------------------------------------------------------------------------------------------------------------
// Files

std::string listing(const std::vector<std::string>& files) {
  std::string text;
  for (const auto& f : files) text += "\n  " + f;
  return text.empty() ? " (none)" : text;
}

/// No temporary `NAME.tmp-PID` left by an atomic write anywhere under `dir`.
::testing::AssertionResult noTemporaries(const fs::path& dir) {
  for (const std::string& file : filesUnder(dir)) {
    if (file.find(".tmp-") != std::string::npos)
      return ::testing::AssertionFailure() << dir << " holds a half-written file: " << file;
  }
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult isPng(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return ::testing::AssertionFailure() << path << " does not exist";
  std::string head = readFile(path).substr(0, 8);
  if (head != std::string("\x89PNG\r\n\x1a\n", 8))
    return ::testing::AssertionFailure() << path << " does not start with the PNG signature";
  return ::testing::AssertionSuccess();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string joinLines(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += line + "\n";
  return text;
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

/// A Python 3 interpreter with NumPy ("" when none): the system one first (a pyenv `python3` may lack NumPy).
std::string pythonWithNumpy() {
  for (std::string candidate : {"/usr/bin/python3", "python3"}) {
    if (capture(candidate + " -c 'import numpy'").status == 0) return candidate;
  }
  return "";
}

// ---------------------------------------------------------------------------------------------------------------------
// The shared body

/// The body folder made by `pixelcloth body --out DIR` (about 5 s), shared read-only by every test.
///
/// gtest_discover_tests runs each test in its own process, so the folder is cached across processes: it is named
/// after the binary's path, size and modification time, built under a pid-named folder and renamed into place only
/// when complete. A rebuilt binary gets a new folder; the folders of its older builds are removed.
struct SharedBody {
  fs::path folder;
  CliRun run;  ///< the `pixelcloth body` run, when this process made the folder
  bool ok = false;
};

const SharedBody& sharedBody() {
  static const SharedBody body = [] {
    SharedBody result;
    const fs::path binary(PIXELCLOTH_BINARY);
    std::error_code ec;
    const auto modified = static_cast<unsigned long long>(fs::last_write_time(binary, ec).time_since_epoch().count());
    const std::string stamp = std::to_string(fs::file_size(binary, ec)) + "-" + std::to_string(modified);
    const fs::path root = fs::temp_directory_path() / "pixelcloth-tests";
    const std::string prefix = "apps-body-" + std::to_string(std::hash<std::string>{}(binary.string())) + "-";
    result.folder = root / (prefix + stamp);
    if (fs::is_directory(result.folder, ec)) {
      result.ok = true;
      return result;
    }
    const fs::path building = root / ("apps-building-body." + std::to_string(::getpid()));
    fs::remove_all(building, ec);
    fs::create_directories(root, ec);
    result.run = runPixelcloth({"body", "--out", building.string()});
    result.ok = result.run.status == 0;
    if (!result.ok) return result;
    fs::rename(building, result.folder, ec);
    if (ec) fs::remove_all(building, ec);  // another process got there first; its folder is just as complete
    for (const auto& entry : fs::directory_iterator(root, ec)) {
      const std::string name = entry.path().filename().string();
      if (startsWith(name, prefix) && entry.path() != result.folder) fs::remove_all(entry.path(), ec);
    }
    return result;
  }();
  return body;
}

/// Positions of the 10 pose joints in a body folder's skeleton.json, as `pixelcloth body --joints` reads them.
nlohmann::json jointsOf(const fs::path& bodyFolder) {
  nlohmann::json skeleton = nlohmann::json::parse(readFile(bodyFolder / "skeleton.json"));
  nlohmann::json joints = nlohmann::json::object();
  for (const auto& joint : skeleton.at("joints")) {
    const std::string name = joint.at("name").get<std::string>();
    if (std::find(kPoseJointNames.begin(), kPoseJointNames.end(), name) != kPoseJointNames.end())
      joints[name] = joint.at("position");
  }
  return {{"joints", joints}};
}

/// Tests that run the CLI in folders of their own (removed again when the test passes).
class CliTest : public ::testing::Test {
 protected:
  void TearDown() override {
    if (HasFailure()) return;  // keep the evidence
    std::error_code ignored;
    for (const auto& dir : dirs_) fs::remove_all(dir, ignored);
  }
  /// A fresh empty folder for this test.
  fs::path dir(const std::string& name) {
    dirs_.push_back(freshDir(name));
    return dirs_.back();
  }

 private:
  std::vector<fs::path> dirs_;
};

/// Tests that need a body folder.
class CliBodyTest : public CliTest {
 protected:
  void SetUp() override {
    const SharedBody& shared = sharedBody();
    ASSERT_TRUE(shared.ok) << "pixelcloth body failed; every body test needs it" << shared.run;
    body_ = shared.folder;
  }
  /// A private copy of the shared body folder, for a test that damages it.
  fs::path copyOfBody() {
    fs::path copy = dir("body");
    fs::copy(body_, copy, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    return copy;
  }
  int bodyVertices() const { return static_cast<int>(core::readMesh(body_ / "body.obj").numVertices()); }

  fs::path body_;
};

// ---------------------------------------------------------------------------------------------------------------------
// The command line itself

TEST_F(CliTest, NoVerbExitsTwo) {
  CliRun run = runPixelcloth({});
  EXPECT_EQ(run.status, 2) << run;
  EXPECT_NE((run.out + run.err).find("subcommand"), std::string::npos) << run;
}

TEST_F(CliTest, UnknownVerbExitsTwo) {
  CliRun run = runPixelcloth({"drape"});
  EXPECT_EQ(run.status, 2) << run;
}

TEST_F(CliTest, HelpOfEveryVerbListsItsOptions) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> verbs = {
      {"body", {"--out", "--shape", "--corrupt-weights", "--corrupt-fraction", "--import", "--joints"}},
      {"garment", {"kind", "tshirt", "necktie", "--out", "--vertices"}},
      {"pose", {"--body", "--pose", "--random", "--seed", "--out"}},
      {"demo", {"--out", "--poses", "--seed"}},
      {"bench", {"--repeats"}},
      {"bases", {"--figures", "--side", "--cells", "--amplitude", "--theta", "--ratio", "--size"}},
      {"images",
       {"--garment", "--values", "--image", "--out", "--width", "--height", "--padding", "default", "--dataset",
        "--samples", "--all"}},
      {"dataset", {"info", "check", "merge", "import", "rebase"}},
      {"edit",
       {"--image", "--out", "--shift", "--inflate", "--inflate-add", "--brush", "--blend", "--mask", "--region",
        "default"}},
      {"cage", {"--garment", "tshirt", "--out", "--size"}},
      {"dress", {"--garment", "tshirt", "necktie", "--body", "--out"}},
      {"generate",
       {"--count", "--seed", "--out", "--garment", "--shard", "--body", "--body-shape", "--corrupt-weights",
        "--threads", "--quiet"}},
      {"markers", {"--garment", "--spacing", "--dataset", "--sample", "--noise", "--dropout", "--pose-out", "--out"}},
      {"reconstruct",
       {"--markers", "--pose", "--body", "--dressing", "--method", "--dataset", "--split", "--noise", "--dropout",
        "--spacing", "--rest-lengths", "--out", "--write-base", "--threads", "--quiet"}},
      {"model", {"--arch", "--width", "--inputs", "--garment", "--values", "--components", "--summary"}},
      {"train",
       {"--dataset", "--model", "--patches", "--width", "--components", "--space", "--residual", "--loss",
        "--normal-weight", "--edge-weight", "--epochs", "--batch", "--lr", "--seed", "--threads", "--out", "--quiet"}},
      {"predict", {"--model", "--pose", "--markers", "--dataset", "--samples", "--base", "--out"}},
      {"evaluate", {"--model", "--dataset", "--split", "--base", "--out"}},
      {"experiments", {"--scale", "small", "full", "--out", "--threads"}},
  };
  for (const auto& [verb, options] : verbs) {
    SCOPED_TRACE(verb);
    CliRun run = runPixelcloth({verb, "--help"});
    EXPECT_EQ(run.status, 0) << run;
    for (const std::string& option : options) EXPECT_NE(run.out.find(option), std::string::npos) << option << run;
  }
  CliRun top = runPixelcloth({"--help"});
  EXPECT_EQ(top.status, 0) << top;
  for (const auto& [verb, options] : verbs) EXPECT_NE(top.out.find(verb), std::string::npos) << verb << top;
}

// ---------------------------------------------------------------------------------------------------------------------
// body

TEST_F(CliBodyTest, BodyWritesFolderWithNormalisedWeights) {
  for (const char* name : {"body.obj", "skeleton.json", "weights.npy", "parts.json"})
    EXPECT_TRUE(fs::is_regular_file(body_ / name)) << name << " missing; the folder has" << listing(filesUnder(body_));
  EXPECT_TRUE(isPng(body_ / "body.png"));
  EXPECT_TRUE(noTemporaries(body_));
  const int vertices = bodyVertices();
  ASSERT_GT(vertices, 1000);

  const std::string python = pythonWithNumpy();
  if (python.empty()) GTEST_SKIP() << "no Python with NumPy: weights.npy not checked with numpy.load";
  CliRun run =
      capture(python + " -c " +
              quote("import sys, numpy\n"
                    "a = numpy.load(sys.argv[1])\n"
                    "print(a.shape[0], a.shape[1], a.dtype, float(abs(a.sum(axis=1) - 1).max()), float(a.min()))") +
              " " + quote((body_ / "weights.npy").string()));
  ASSERT_EQ(run.status, 0) << run;
  std::istringstream in(run.out);
  int rows = 0, cols = 0;
  std::string dtype;
  double rowSumError = 1, minimum = -1;
  in >> rows >> cols >> dtype >> rowSumError >> minimum;
  EXPECT_EQ(rows, vertices) << run;
  EXPECT_EQ(cols, 12) << run;
  EXPECT_EQ(dtype, "float32") << run;
  EXPECT_LT(rowSumError, 1e-5) << run;
  EXPECT_GE(minimum, 0.0) << run;
}

TEST_F(CliTest, BodyRefusesShapeOutOfRange) {
  fs::path out = dir("out") / "body";
  EXPECT_TRUE(
      refused(runPixelcloth({"body", "--out", out.string(), "--shape", "5"}), {"--shape", "5", "not in range"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliTest, BodyRefusesUnknownCorruptMode) {
  fs::path out = dir("out") / "body";
  EXPECT_TRUE(refused(runPixelcloth({"body", "--out", out.string(), "--corrupt-weights", "legs"}),
                      {"--corrupt-weights", "legs", "torso"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliTest, BodyImportNamesMissingMesh) {
  fs::path work = dir("work");
  fs::path joints = work / "j.json";
  nlohmann::json positions = nlohmann::json::object();
  for (const auto& name : kPoseJointNames) positions[name] = {0.0, 1.2, 0.0};
  writeFile(joints, nlohmann::json{{"joints", positions}}.dump());
  fs::path out = work / "out";
  fs::path missing = work / "missing.obj";
  EXPECT_TRUE(
      refused(runPixelcloth({"body", "--import", missing.string(), "--joints", joints.string(), "--out", out.string()}),
              {missing.string(), "no such file"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliTest, BodyImportNeedsJoints) {
  fs::path out = dir("out") / "body";
  EXPECT_TRUE(
      refused(runPixelcloth({"body", "--import", "mesh.obj", "--out", out.string()}), {"--import", "--joints"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, ImportRefusesOpenMesh) {
  fs::path work = dir("work");
  // The mannequin without its first five faces: a hole.
  std::vector<std::string> kept;
  int dropped = 0;
  for (const std::string& line : lines(readFile(body_ / "body.obj"))) {
    if (startsWith(line, "f ") && dropped < 5) {
      ++dropped;
      continue;
    }
    kept.push_back(line);
  }
  ASSERT_EQ(dropped, 5);
  fs::path mesh = work / "open.obj", joints = work / "joints.json", out = work / "out";
  writeFile(mesh, joinLines(kept));
  writeFile(joints, jointsOf(body_).dump(2));
  EXPECT_TRUE(
      refused(runPixelcloth({"body", "--import", mesh.string(), "--joints", joints.string(), "--out", out.string()}),
              {mesh.string(), "closed and manifold"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, ImportRefusesUnknownJoint) {
  fs::path work = dir("work");
  nlohmann::json joints = jointsOf(body_);
  joints["joints"]["l_elbow"] = {0.5, 1.45, 0.0};
  fs::path jointsFile = work / "joints.json", out = work / "out";
  writeFile(jointsFile, joints.dump(2));
  EXPECT_TRUE(refused(runPixelcloth({"body", "--import", (body_ / "body.obj").string(), "--joints", jointsFile.string(),
                                     "--out", out.string()}),
                      {jointsFile.string(), "l_elbow"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, ImportRefusesJointOutsideBody) {
  fs::path work = dir("work");
  nlohmann::json joints = jointsOf(body_);
  joints["joints"]["neck"] = {0.0, 1.5, 2.0};  // two metres in front of the chest
  fs::path jointsFile = work / "joints.json", out = work / "out";
  writeFile(jointsFile, joints.dump(2));
  fs::path mesh = body_ / "body.obj";
  EXPECT_TRUE(refused(
      runPixelcloth({"body", "--import", mesh.string(), "--joints", jointsFile.string(), "--out", out.string()}),
      {mesh.string(), "neck", "outside"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, ImportRefusesJointCoordinateTooLargeForADouble) {
  fs::path work = dir("work");
  std::string text = jointsOf(body_).dump(2);
  const size_t neck = text.find("\"neck\"");
  ASSERT_NE(neck, std::string::npos);
  const size_t x = text.find('[', neck) + 1;
  text.replace(x, text.find(',', x) - x, "1e400");  // valid JSON, but no double holds it
  fs::path jointsFile = work / "joints.json", out = work / "out";
  writeFile(jointsFile, text);
  EXPECT_TRUE(refused(runPixelcloth({"body", "--import", (body_ / "body.obj").string(), "--joints", jointsFile.string(),
                                     "--out", out.string()}),
                      {jointsFile.string(), "1e400"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, ImportRefusesNanCoordinate) {
  fs::path work = dir("work");
  std::vector<std::string> text = lines(readFile(body_ / "body.obj"));
  auto firstVertex = std::find_if(text.begin(), text.end(), [](const std::string& l) { return startsWith(l, "v "); });
  ASSERT_NE(firstVertex, text.end());
  *firstVertex = "v nan 0 0";
  fs::path mesh = work / "nan.obj", joints = work / "joints.json", out = work / "out";
  writeFile(mesh, joinLines(text));
  writeFile(joints, jointsOf(body_).dump(2));
  EXPECT_TRUE(
      refused(runPixelcloth({"body", "--import", mesh.string(), "--joints", joints.string(), "--out", out.string()}),
              {mesh.string(), "vertex 1"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, ImportOfMannequinWritesBodyFolder) {
  fs::path work = dir("work");
  fs::path joints = work / "joints.json", out = work / "out";
  writeFile(joints, jointsOf(body_).dump(2));
  CliRun run = runPixelcloth(
      {"body", "--import", (body_ / "body.obj").string(), "--joints", joints.string(), "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  for (const char* name : {"body.obj", "skeleton.json", "weights.npy", "parts.json"})
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name << " missing; the folder has" << listing(filesUnder(out));
  EXPECT_TRUE(isPng(out / "body.png"));
  EXPECT_TRUE(noTemporaries(out));
  core::NpyArray weights = core::readNpy(out / "weights.npy");
  EXPECT_EQ(weights.dtype, "<f4");
  EXPECT_EQ(weights.shape, (std::vector<std::int64_t>{bodyVertices(), 12}));
}

// ---------------------------------------------------------------------------------------------------------------------
// pose

TEST_F(CliBodyTest, PoseRandomWritesMeshesAndPoseArray) {
  fs::path out = dir("out") / "posed";
  CliRun run = runPixelcloth({"pose", "--body", body_.string(), "--random", "3", "--seed", "1", "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  const int vertices = bodyVertices();
  for (const char* name : {"posed_000.obj", "posed_001.obj", "posed_002.obj"}) {
    ASSERT_TRUE(fs::is_regular_file(out / name)) << name << " missing; the folder has" << listing(filesUnder(out));
    EXPECT_EQ(core::readMesh(out / name).numVertices(), vertices) << name;
  }
  EXPECT_FALSE(fs::exists(out / "posed_003.obj"));
  core::NpyArray poses = core::readNpy(out / "poses.npy");
  EXPECT_EQ(poses.dtype, "<f4");
  EXPECT_EQ(poses.shape, (std::vector<std::int64_t>{3, 90}));
  nlohmann::json list = nlohmann::json::parse(readFile(out / "poses.json"));
  ASSERT_TRUE(list.contains("poses")) << list.dump().substr(0, 500);
  EXPECT_EQ(list["poses"].size(), 3u);
  EXPECT_TRUE(isPng(out / "posed.png"));
  EXPECT_TRUE(noTemporaries(out));
}

TEST_F(CliBodyTest, PoseRefusesWeightsOfWrongVertexCount) {
  fs::path body = copyOfBody(), out = dir("out") / "posed";
  core::writeNpy(body / "weights.npy", Eigen::MatrixXf::Constant(100, 12, 1.0f / 12).eval());
  EXPECT_TRUE(
      refused(runPixelcloth({"pose", "--body", body.string(), "--random", "3", "--out", out.string()}),
              {(body / "weights.npy").string(), "(100, 12)", "expected (" + std::to_string(bodyVertices()) + ", 12)"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, PoseRefusesTruncatedWeights) {
  fs::path body = copyOfBody(), out = dir("out") / "posed";
  std::string bytes = readFile(body / "weights.npy");
  writeFile(body / "weights.npy", bytes.substr(0, bytes.size() / 2));
  EXPECT_TRUE(refused(runPixelcloth({"pose", "--body", body.string(), "--random", "3", "--out", out.string()}),
                      {(body / "weights.npy").string(), "truncated"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, PoseRefusesFloat64Weights) {
  fs::path body = copyOfBody(), out = dir("out") / "posed";
  core::writeNpy(body / "weights.npy", Eigen::MatrixXd::Constant(bodyVertices(), 12, 1.0 / 12).eval());
  EXPECT_TRUE(refused(runPixelcloth({"pose", "--body", body.string(), "--random", "3", "--out", out.string()}),
                      {(body / "weights.npy").string(), "<f8", "float32"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliTest, PoseRefusesMissingBodyFolder) {
  fs::path work = dir("work");
  fs::path body = work / "no-such-body", out = work / "posed";
  EXPECT_TRUE(refused(runPixelcloth({"pose", "--body", body.string(), "--random", "3", "--out", out.string()}),
                      {body.string(), "body folder"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

TEST_F(CliBodyTest, PoseRefusesInvalidSkeletonJson) {
  fs::path body = copyOfBody(), out = dir("out") / "posed";
  writeFile(body / "skeleton.json", "{\"joints\": [ {\"name\": \"root\", ");
  EXPECT_TRUE(refused(runPixelcloth({"pose", "--body", body.string(), "--random", "3", "--out", out.string()}),
                      {(body / "skeleton.json").string(), "JSON"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
}

/// Runs `pixelcloth pose --pose FILE` on the shared body with `pose` written to FILE.
class CliPoseFileTest : public CliBodyTest {
 protected:
  CliRun poseWith(const std::string& text) {
    fs::path work = dir("work");
    poseFile_ = work / "p.json";
    out_ = work / "posed";
    writeFile(poseFile_, text);
    return runPixelcloth({"pose", "--body", body_.string(), "--pose", poseFile_.string(), "--out", out_.string()});
  }
  CliRun poseWith(const nlohmann::json& pose) { return poseWith(pose.dump()); }
  fs::path poseFile_, out_;
};

TEST_F(CliPoseFileTest, RefusesUnknownJoint) {
  CliRun run = poseWith({{"joints", {{"l_elbow", {{"euler_deg", {0, 0, -60}}}}}}});
  EXPECT_TRUE(refused(run, {poseFile_.string(), "l_elbow"}));
  EXPECT_TRUE(filesUnder(out_).empty()) << listing(filesUnder(out_));
}

TEST_F(CliPoseFileTest, RefusesMatrixThatIsNotARotation) {
  CliRun run = poseWith({{"joints", {{"neck", {{"rotation", std::vector<double>(9, 2.0)}}}}}});
  EXPECT_TRUE(refused(run, {poseFile_.string(), "neck", "rotation"}));
  EXPECT_TRUE(filesUnder(out_).empty()) << listing(filesUnder(out_));
}

TEST_F(CliPoseFileTest, RefusesPoseVectorOfTwos) {
  CliRun run = poseWith({{"pose", std::vector<double>(90, 2.0)}});
  EXPECT_TRUE(refused(run, {poseFile_.string(), "rotation"}));
  EXPECT_TRUE(filesUnder(out_).empty()) << listing(filesUnder(out_));
}

TEST_F(CliPoseFileTest, RefusesPoseVectorOf89Numbers) {
  std::vector<double> pose;
  for (int k = 0; k < 10; ++k) pose.insert(pose.end(), {1, 0, 0, 0, 1, 0, 0, 0, 1});
  pose.pop_back();
  CliRun run = poseWith({{"pose", pose}});
  EXPECT_TRUE(refused(run, {poseFile_.string(), "90", "89"}));
  EXPECT_TRUE(filesUnder(out_).empty()) << listing(filesUnder(out_));
}

/// JSON has no NaN or infinity, but a number too large for a double is valid JSON: nlohmann throws
/// out_of_range.406 for it, not parse_error.
TEST_F(CliPoseFileTest, RefusesNumberTooLargeForADouble) {
  CliRun run = poseWith(std::string(R"({"joints": {"neck": {"euler_deg": [0, 0, 1e400]}}})"));
  EXPECT_TRUE(refused(run, {poseFile_.string(), "1e400"}));
  EXPECT_TRUE(filesUnder(out_).empty()) << listing(filesUnder(out_));
}

TEST_F(CliPoseFileTest, LoweringTheLeftArmLowersTheLeftHand) {
  CliRun run = poseWith({{"joints", {{"l_arm", {{"euler_deg", {0, 0, -60}}}}}}});
  ASSERT_EQ(run.status, 0) << run;
  core::Mesh rest = core::readMesh(body_ / "body.obj");
  core::Mesh posed = core::readMesh(out_ / "posed_000.obj");
  ASSERT_EQ(posed.numVertices(), rest.numVertices());
  ASSERT_EQ(posed.numFaces(), rest.numFaces());
  Eigen::Index leftTip = 0, rightTip = 0;  // the wearer's left is +x
  rest.V.col(0).maxCoeff(&leftTip);
  rest.V.col(0).minCoeff(&rightTip);
  // Arm from the shoulder to the fingertips is ~0.7 m: lowered by 60 degrees, the tip drops by about 0.6 m.
  EXPECT_LT(posed.V(leftTip, 1), rest.V(leftTip, 1) - 0.4)
      << "left hand tip y: rest " << rest.V(leftTip, 1) << ", posed " << posed.V(leftTip, 1);
  EXPECT_NEAR(posed.V(rightTip, 1), rest.V(rightTip, 1), 1e-4) << "the right arm stays at rest";
  EXPECT_TRUE(isPng(out_ / "posed.png"));
  EXPECT_TRUE(noTemporaries(out_));
}

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

// ---------------------------------------------------------------------------------------------------------------------
// bench and demo

// The stitch group (two PCA fits at full size, two minutes) shares the procedural and learned groups' printing and is
// left out here.
TEST_F(CliTest, BenchPrintsOnlyJsonLines) {
  for (const char* group : {"procedural", "learn"}) {
    CliRun run = runPixelcloth({"bench", "--repeats", "1", "--only", group});
    ASSERT_EQ(run.status, 0) << run;
    int figures = 0;
    for (const std::string& line : lines(run.out)) {
      SCOPED_TRACE(line);
      nlohmann::json figure = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
      ASSERT_TRUE(figure.is_object()) << "not a JSON object";
      for (const char* key : {"name", "value", "unit", "goal"}) EXPECT_TRUE(figure.contains(key)) << key;
      EXPECT_TRUE(figure["name"].is_string());
      EXPECT_TRUE(figure["value"].is_number());
      EXPECT_TRUE(figure["unit"].is_string());
      EXPECT_TRUE(figure["goal"].is_number());
      ++figures;
    }
    EXPECT_GT(figures, 0) << run;
  }
}

TEST_F(CliTest, DemoWritesReportWhosePicturesExist) {
  fs::path out = dir("out") / "report";
  CliRun run = runPixelcloth({"demo", "--out", out.string(), "--poses", "2", "--filter-poses", "16", "--tshirt-samples",
                              "10", "--own-garment-samples", "8"});
  ASSERT_EQ(run.status, 0) << run;
  ASSERT_TRUE(fs::is_regular_file(out / "index.html")) << listing(filesUnder(out));
  EXPECT_NO_THROW(nlohmann::json::parse(readFile(out / "report.json")));
  const std::string html = readFile(out / "index.html");
  const std::regex img(R"(<img[^>]*\ssrc\s*=\s*['"]([^'"]+)['"])", std::regex::icase);
  int pictures = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), img); it != std::sregex_iterator(); ++it) {
    const std::string src = (*it)[1].str();
    EXPECT_TRUE(isPng(out / src)) << "index.html shows " << src;
    ++pictures;
  }
  EXPECT_GT(pictures, 0) << "index.html shows no pictures";
  EXPECT_TRUE(noTemporaries(out));
  // The imported T-shirt OBJ went through the pipeline as a garment folder, and its dataset carries it.
  EXPECT_NE(html.find("Your own garment"), std::string::npos);
  EXPECT_TRUE(isPng(out / "own_garment" / "predictions.png"));
  EXPECT_EQ(nlohmann::json::parse(readFile(out / "own_garment" / "dataset" / "manifest.json"))["garment"], "my_shirt");
  // Fitted to the body: it carries the template's cage lines, and a decoder per patch was trained on it.
  const nlohmann::json fitted = nlohmann::json::parse(readFile(out / "own_garment" / "garment" / "garment.json"));
  EXPECT_GE(fitted.at("cage_lines").size(), 10u);
  EXPECT_TRUE(fs::is_regular_file(out / "own_garment" / "model_patch" / "patch_00" / "model.json"))
      << listing(filesUnder(out / "own_garment" / "model_patch"));

  // Run again into the same folder, as a user does after pulling: the datasets are made afresh, so the models the first
  // run left were trained on other samples; the demo retrains them instead of refusing to resume.
  run = runPixelcloth({"demo", "--out", out.string(), "--poses", "2", "--filter-poses", "16", "--tshirt-samples", "10",
                       "--own-garment-samples", "8"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(noTemporaries(out));
}

// ---------------------------------------------------------------------------------------------------------------------
// images and edit

/// Smooth centimetre-sized offsets of the default T-shirt, #V x 3.
Eigen::MatrixXf shirtOffsets() {
  static const garment::Garment shirt = garment::makeTShirt();
  Eigen::MatrixXf x(shirt.mesh.numVertices(), 3);
  for (int v = 0; v < x.rows(); ++v) {
    Eigen::Vector3d p = shirt.mesh.V.row(v);
    x.row(v) << 0.02 * std::sin(6 * p.x()), 0.01 * std::cos(5 * p.y()), 0.015 * std::sin(4 * p.x() + 3 * p.y());
  }
  return x;
}

TEST_F(CliTest, ImagesRoundTripThroughExr) {
  fs::path work = dir("work");
  Eigen::MatrixXf x = shirtOffsets();
  core::writeNpy(work / "values.npy", x);
  CliRun run = runPixelcloth(
      {"images", "--garment", "tshirt", "--values", (work / "values.npy").string(), "--out", (work / "img").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(isPng(work / "img" / "cloth.png"));
  core::ExrImage exr = core::readExr(work / "img" / "cloth.exr");
  EXPECT_EQ(exr.width, 256);
  EXPECT_TRUE(exr.hasChannel("front.du") && exr.hasChannel("back.mask"));
  run = runPixelcloth({"images", "--garment", "tshirt", "--image", (work / "img" / "cloth.exr").string(), "--out",
                       (work / "back.npy").string()});
  ASSERT_EQ(run.status, 0) << run;
  Eigen::MatrixXf back = core::readNpyMatrixF(work / "back.npy", x.rows(), 3);
  EXPECT_LT((back - x).cwiseAbs().maxCoeff(), 2e-4);
  EXPECT_TRUE(noTemporaries(work));
}

TEST_F(CliTest, ImagesRefusesWrongVertexCountAndCorruptedExr) {
  fs::path work = dir("work");
  core::writeNpy(work / "few.npy", Eigen::MatrixXf::Zero(10, 3).eval());
  const std::string rows = std::to_string(shirtOffsets().rows());
  EXPECT_TRUE(refused(runPixelcloth({"images", "--garment", "tshirt", "--values", (work / "few.npy").string(), "--out",
                                     (work / "img").string()}),
                      {"few.npy", "(10, 3)", "(" + rows + ", 3)"}));
  EXPECT_TRUE(filesUnder(work / "img").empty());
  writeFile(work / "bad.exr", "v/1 this is not an EXR file");
  EXPECT_TRUE(refused(runPixelcloth({"images", "--garment", "tshirt", "--image", (work / "bad.exr").string(), "--out",
                                     (work / "v.npy").string()}),
                      {"bad.exr"}));
  EXPECT_FALSE(fs::exists(work / "v.npy"));
}

TEST_F(CliTest, EditShiftWritesExrAndPreview) {
  fs::path work = dir("work");
  core::writeNpy(work / "values.npy", shirtOffsets());
  ASSERT_EQ(runPixelcloth(
                {"images", "--garment", "tshirt", "--values", (work / "values.npy").string(), "--out", work.string()})
                .status,
            0);
  CliRun run = runPixelcloth({"edit", "--image", (work / "cloth.exr").string(), "--out",
                              (work / "shifted.exr").string(), "--shift", "0.01", "0"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(isPng(work / "shifted.png"));
  core::ExrImage before = core::readExr(work / "cloth.exr"), after = core::readExr(work / "shifted.exr");
  Eigen::MatrixXf inside = (before.channel("front.mask").array() > 0).cast<float>();
  EXPECT_NEAR((after.channel("front.du") - before.channel("front.du")).maxCoeff(), 0.01, 1e-6);
  EXPECT_NEAR(
      ((after.channel("front.du") - before.channel("front.du")).array() * (1 - inside.array())).abs().maxCoeff(), 0,
      1e-9);
  EXPECT_EQ(after.channel("front.dn"), before.channel("front.dn"));
  EXPECT_TRUE(refused(runPixelcloth({"edit", "--image", (work / "cloth.exr").string(), "--out",
                                     (work / "x.exr").string(), "--shift", "0.01", "0", "--inflate", "2"}),
                      {"exactly one"}));
  EXPECT_TRUE(refused(runPixelcloth({"edit", "--image", (work / "missing.exr").string(), "--out",
                                     (work / "x.exr").string(), "--inflate", "2"}),
                      {"missing.exr"}));
}

// ---------------------------------------------------------------------------------------------------------------------
// dataset

/// A necktie sequence to import on the shared body: a dressing folder (body/, rest_positions.npy, embedding arrays),
/// OBJ frames of the tie moved a little, and identity poses (36 numbers per row) as CSV.
class CliDatasetTest : public CliBodyTest {
 protected:
  void SetUp() override {
    CliBodyTest::SetUp();
    if (HasFatalFailure()) return;
    work_ = dir("work");
    tie_ = garment::makeNecktie();
    fs::create_directories(work_ / "dressing");
    fs::copy(body_, work_ / "dressing" / "body", fs::copy_options::recursive);
    const core::Mesh body = core::readMesh(body_ / "body.obj");
    const Eigen::MatrixX3d u = Eigen::RowVector3d(1, 0, 0).replicate(tie_.mesh.numVertices(), 1);
    garment::saveEmbedding(work_ / "dressing", garment::embedClosest(body.V, body.F, tie_.mesh.V, u));
    core::writeNpy(work_ / "dressing" / "rest_positions.npy", Eigen::MatrixXd(tie_.mesh.V));
    std::string csv = "# 36 numbers per frame\n";
    for (int i = 0; i < 3; ++i) {
      core::Mesh frame = tie_.mesh;
      frame.V.col(2).array() += 0.005 * i;
      core::writeMesh(work_ / "objs" / ("tie_" + std::to_string(i) + ".obj"), frame);
      for (int j = 0; j < 4; ++j) csv += std::string(j ? "," : "") + "1,0,0,0,1,0,0,0,1";
      csv += "\n";
    }
    writeFile(work_ / "poses.csv", csv);
  }
  CliRun import(const fs::path& objs, const fs::path& poses, const fs::path& out) {
    return runPixelcloth({"dataset", "import", "--garment", "necktie", "--objs", objs.string(), "--poses",
                          poses.string(), "--dressing", (work_ / "dressing").string(), "--out", out.string(),
                          "--quiet"});
  }

  fs::path work_;
  garment::Garment tie_;
};

TEST_F(CliDatasetTest, ImportInfoCheckMergeImages) {
  const fs::path data = work_ / "data";
  CliRun run = import(work_ / "objs", work_ / "poses.csv", data);
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(noTemporaries(data));
  EXPECT_FALSE(fs::exists(data / "partial"));

  run = runPixelcloth({"dataset", "check", data.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(startsWith(run.out, "ok")) << run;

  run = runPixelcloth({"dataset", "info", data.string()});
  ASSERT_EQ(run.status, 0) << run;
  for (const char* text : {"necktie", "imported", "samples      3", "splits", "penetration", "rejected"})
    EXPECT_NE(run.out.find(text), std::string::npos) << text << run;
  run = runPixelcloth({"dataset", "info", "--json", data.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json info = nlohmann::json::parse(run.out);
  EXPECT_EQ(info["rows"], 3);
  EXPECT_EQ(info["pose_size"], 36);
  EXPECT_TRUE(info["stats"].contains("max_penetration_mm"));
  EXPECT_EQ(info["counts"]["train"].get<int>() + info["counts"]["regularisation"].get<int>() +
                info["counts"]["test"].get<int>(),
            3);

  run = runPixelcloth({"dataset", "merge", "--out", (work_ / "merged").string(), data.string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(readFile(work_ / "merged" / "offsets.npy"), readFile(data / "offsets.npy"));
  EXPECT_EQ(runPixelcloth({"dataset", "check", (work_ / "merged").string()}).status, 0);

  run = runPixelcloth({"images", "--dataset", data.string(), "--all", "--out", (work_ / "images").string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(isPng(work_ / "images" / ("cloth_00000" + std::to_string(i) + ".png")));
    const core::ExrImage exr = core::readExr(work_ / "images" / ("cloth_00000" + std::to_string(i) + ".exr"));
    EXPECT_TRUE(exr.hasChannel("du") || exr.hasChannel("tie.du"));
  }
  EXPECT_TRUE(refused(
      runPixelcloth({"images", "--dataset", data.string(), "--samples", "7", "--out", (work_ / "more").string()}),
      {"--samples 7", "0 to 2"}));

  // A damaged copy: check and merge refuse it, naming the file.
  fs::copy(data, work_ / "damaged", fs::copy_options::recursive);
  std::string bytes = readFile(data / "positions.npy");
  bytes[bytes.size() - 5] ^= 0x40;
  writeFile(work_ / "damaged" / "positions.npy", bytes);
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "check", (work_ / "damaged").string()}), {"positions.npy", "CRC-32"}));
  EXPECT_TRUE(
      refused(runPixelcloth({"dataset", "merge", "--out", (work_ / "merged2").string(), (work_ / "damaged").string()}),
              {"positions.npy", "CRC-32"}));
  EXPECT_FALSE(fs::exists(work_ / "merged2" / "manifest.json"));
}

TEST_F(CliDatasetTest, RebaseOntoABodyFolderAndRefuseADatasetAsTheBody) {
  const fs::path data = work_ / "data";
  ASSERT_EQ(import(work_ / "objs", work_ / "poses.csv", data).status, 0);
  const fs::path rebased = work_ / "rebased";
  CliRun run = runPixelcloth({"dataset", "rebase", data.string(), "--body", body_.string(), "--out", rebased.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_NE(run.out.find("rebased 3 samples"), std::string::npos) << run;
  EXPECT_EQ(runPixelcloth({"dataset", "check", rebased.string()}).status, 0);
  EXPECT_EQ(readFile(rebased / "positions.npy"), readFile(data / "positions.npy"));
  const nlohmann::json manifest = nlohmann::json::parse(readFile(rebased / "manifest.json"));
  EXPECT_EQ(manifest["body"]["rebased_from"]["folder"], fs::absolute(data).lexically_normal().string());

  EXPECT_TRUE(refused(runPixelcloth({"dataset", "rebase", data.string(), "--body", data.string(), "--out",
                                     (work_ / "wrong").string()}),
                      {"is a dataset folder", "body folder", (data / "body").string()}));
  EXPECT_FALSE(fs::exists(work_ / "wrong"));
}

TEST_F(CliDatasetTest, RefusesBadInputsNamingTheFile) {
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "check", (work_ / "nowhere").string()}), {"nowhere", "no such"}));
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "info", (work_ / "objs").string()}), {"manifest.json"}));
  EXPECT_TRUE(refused(
      runPixelcloth({"dataset", "merge", "--out", (work_ / "m").string(), (work_ / "nowhere").string()}), {"nowhere"}));

  // An OBJ of another vertex count.
  fs::copy(work_ / "objs", work_ / "objs_few", fs::copy_options::recursive);
  core::Mesh few;
  few.V = tie_.mesh.V.topRows(3);
  few.F.resize(1, 3);
  few.F << 0, 1, 2;
  core::writeMesh(work_ / "objs_few" / "tie_1.obj", few);
  EXPECT_TRUE(refused(import(work_ / "objs_few", work_ / "poses.csv", work_ / "out1"), {"tie_1.obj", "3 vertices"}));
  EXPECT_FALSE(fs::exists(work_ / "out1"));

  // A NaN coordinate in an OBJ.
  fs::copy(work_ / "objs", work_ / "objs_nan", fs::copy_options::recursive);
  std::string text = readFile(work_ / "objs_nan" / "tie_2.obj");
  const size_t v = text.find("\nv ");
  ASSERT_NE(v, std::string::npos);
  text.replace(v, 4, "\nv nan ");
  writeFile(work_ / "objs_nan" / "tie_2.obj", text);
  EXPECT_TRUE(refused(import(work_ / "objs_nan", work_ / "poses.csv", work_ / "out2"), {"tie_2.obj"}));
  EXPECT_FALSE(fs::exists(work_ / "out2"));

  // A pose CSV with a wrong column count, and fewer poses than frames.
  writeFile(work_ / "short.csv", "1,0,0,0,1,0,0,0,1\n");
  EXPECT_TRUE(refused(import(work_ / "objs", work_ / "short.csv", work_ / "out3"),
                      {"short.csv", "line 1", "9 columns, expected 36"}));
  std::string two = readFile(work_ / "poses.csv");
  two = two.substr(0, two.rfind('\n', two.size() - 2) + 1);
  writeFile(work_ / "two.csv", two);
  EXPECT_TRUE(refused(import(work_ / "objs", work_ / "two.csv", work_ / "out4"), {"two.csv", "2 poses for 3 OBJ"}));
  EXPECT_FALSE(fs::exists(work_ / "out4"));
}

}  // namespace
}  // namespace pixelcloth::apps

namespace pixelcloth::apps {
namespace {

TEST_F(CliBodyTest, GenerateMakesACheckedNecktieDatasetAndResumes) {
  const fs::path out = dir("generate_necktie");
  const fs::path data = out / "tie";
  const CliRun first = runPixelcloth({"generate", "--garment", "necktie", "--count", "3", "--seed", "5", "--body",
                                      body_.string(), "--out", data.string()});
  ASSERT_EQ(first.status, 0) << first;
  for (const char* name : {"manifest.json", "poses.npy", "positions.npy", "offsets.npy", "split.npy"})
    EXPECT_TRUE(fs::exists(data / name)) << name;
  const CliRun check = runPixelcloth({"dataset", "check", data.string()});
  EXPECT_EQ(check.status, 0) << check;
  EXPECT_NE(check.out.find("ok"), std::string::npos) << check;
  const nlohmann::json manifest = nlohmann::json::parse(readFile(data / "manifest.json"));
  EXPECT_EQ(manifest["pose_size"], 36);
  EXPECT_EQ(manifest["stats"]["accepted"], 3);
  EXPECT_LE(manifest["stats"]["max_penetration_mm"].get<double>(), 2.0);
  // A necktie decoder learns from it; a whole-garment one does not fit the tie's images, and says so.
  const fs::path model = out / "model";
  const CliRun train = runPixelcloth({"train", "--dataset", data.string(), "--model", "necktie", "--width", "0.125",
                                      "--epochs", "2", "--batch", "2", "--out", model.string(), "--quiet"});
  ASSERT_EQ(train.status, 0) << train;
  for (const char* name : {"model.tensors", "model.json", "log.csv"}) EXPECT_TRUE(fs::exists(model / name)) << name;
  EXPECT_EQ(nlohmann::json::parse(readFile(model / "model.json"))["architecture"], "necktie");
  EXPECT_TRUE(refused(runPixelcloth({"train", "--dataset", data.string(), "--model", "whole", "--epochs", "1", "--out",
                                     (out / "whole").string()}),
                      {"whole model does not fit", "necktie"}));
  EXPECT_FALSE(fs::exists(out / "whole" / "model.tensors"));
  // The same command again finds everything done and changes nothing.
  const std::string before = readFile(data / "positions.npy");
  const CliRun again = runPixelcloth({"generate", "--garment", "necktie", "--count", "3", "--seed", "5", "--body",
                                      body_.string(), "--out", data.string()});
  EXPECT_EQ(again.status, 0) << again;
  EXPECT_NE(again.err.find("0 samples simulated (3 already done"), std::string::npos) << again;
  EXPECT_EQ(readFile(data / "positions.npy"), before);
}

TEST_F(CliTest, GenerateRefusesBadSettings) {
  const fs::path out = dir("generate_bad");
  const CliRun zero = runPixelcloth({"generate", "--count", "0", "--out", (out / "a").string()});
  EXPECT_EQ(zero.status, 2) << zero;
  EXPECT_NE(zero.err.find("--count"), std::string::npos) << zero;
  const CliRun shard = runPixelcloth({"generate", "--count", "4", "--shard", "3/2", "--out", (out / "b").string()});
  EXPECT_EQ(shard.status, 2) << shard;
  EXPECT_NE(shard.err.find("3/2"), std::string::npos) << shard;
  const CliRun garment =
      runPixelcloth({"generate", "--count", "4", "--garment", "skirt", "--out", (out / "c").string()});
  EXPECT_EQ(garment.status, 2) << garment;
  EXPECT_NE(garment.err.find("skirt"), std::string::npos) << garment;
  const CliRun body =
      runPixelcloth({"generate", "--count", "4", "--body", (out / "nowhere").string(), "--out", (out / "d").string()});
  EXPECT_EQ(body.status, 2) << body;
  EXPECT_NE(body.err.find("nowhere"), std::string::npos) << body;
}

}  // namespace
}  // namespace pixelcloth::apps

namespace pixelcloth::apps {
namespace {

// ---------------------------------------------------------------------------------------------------------------------
// markers and reconstruct (DESIGN.md, "Key-point-to-cage spline solver")

/// A necktie dataset imported from frames of the rest tie wrapped around horizontal cylinders of a few radii (an
/// isometric bend: the pattern lengths stay true), on the shared body; reconstructed from its own markers.
class CliReconstructTest : public CliDatasetTest {
 protected:
  void SetUp() override {
    CliDatasetTest::SetUp();
    if (HasFatalFailure()) return;
    const double top = tie_.mesh.V.col(1).maxCoeff();
    std::string csv;
    for (int i = 0; i < 3; ++i) {
      core::Mesh frame = tie_.mesh;
      const double radius = 0.25 + 0.1 * i;
      for (int v = 0; v < frame.numVertices(); ++v) {
        const double angle = (top - tie_.mesh.V(v, 1)) / radius;
        frame.V(v, 1) = top - radius * std::sin(angle);
        frame.V(v, 2) = tie_.mesh.V(v, 2) + radius * (1 - std::cos(angle));
      }
      core::writeMesh(work_ / "bent" / ("tie_" + std::to_string(i) + ".obj"), frame);
      for (int j = 0; j < 4; ++j) csv += std::string(j ? "," : "") + "1,0,0,0,1,0,0,0,1";
      csv += "\n";
    }
    writeFile(work_ / "bent.csv", csv);
    const CliRun run = import(work_ / "bent", work_ / "bent.csv", work_ / "bent_data");
    ASSERT_EQ(run.status, 0) << run;
    data_ = work_ / "bent_data";
  }
  fs::path data_;
};

TEST_F(CliReconstructTest, DatasetFormWritesMetricsForEveryMethodAndTheSplineBeatsLinear) {
  const fs::path out = work_ / "rec";
  const CliRun run = runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "all", "--spacing", "0.08",
                                    "--out", out.string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(noTemporaries(out));
  const nlohmann::json metrics = nlohmann::json::parse(readFile(out / "metrics.json"));
  EXPECT_EQ(metrics["samples"], 3);
  for (const char* method : {"linear", "catmull_rom", "spline", "spline_anisotropic"}) {
    SCOPED_TRACE(method);
    ASSERT_TRUE(metrics["methods"].contains(method)) << metrics.dump(2);
    const double cage = metrics["methods"][method]["cage_cm"], garment = metrics["methods"][method]["garment_cm"];
    EXPECT_TRUE(std::isfinite(cage) && std::isfinite(garment));
    EXPECT_GE(cage, 0);
    EXPECT_LT(garment, 1.0) << "a bent tie rebuilt from markers 8 cm apart";
    EXPECT_TRUE(metrics["methods"][method]["curves"].contains("outline"));
    EXPECT_GE(metrics["methods"][method]["pushed_out_percent"].get<double>(), 0);
  }
  EXPECT_LT(metrics["methods"]["spline"]["cage_cm"].get<double>(),
            metrics["methods"]["linear"]["cage_cm"].get<double>());
  EXPECT_TRUE(isPng(out / "error_maps.png"));
  EXPECT_TRUE(fs::is_regular_file(out / "markers.json"));
  // The spline's length model, fitted on the training split (these garments are bent without stretch: worn lengths
  // near the rest lengths).
  ASSERT_TRUE(metrics["length_model"].is_object()) << metrics.dump(2);
  EXPECT_GT(metrics["length_model"]["samples"].get<int>(), 0);
  const nlohmann::json model = nlohmann::json::parse(readFile(out / "length_model.json"));
  EXPECT_EQ(model["garment"], "necktie");
  EXPECT_DOUBLE_EQ(model["marker_spacing_m"].get<double>(), 0.08);
  EXPECT_TRUE(model["curves"].contains("outline"));
  EXPECT_EQ(core::readMesh(out / "sample_000000" / "spline.obj").numVertices(), tie_.mesh.numVertices());
  EXPECT_TRUE(fs::is_regular_file(out / "sample_000000" / "truth.obj"));

  // Captured markers: noisy (fitted softly) and with a third of the curve markers missing; still solved.
  const CliRun noisy =
      runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "all", "--noise", "0.3", "--dropout", "0.3",
                     "--seed", "2", "--out", (work_ / "noisy").string(), "--quiet"});
  ASSERT_EQ(noisy.status, 0) << noisy;
  const nlohmann::json captured = nlohmann::json::parse(readFile(work_ / "noisy" / "metrics.json"));
  EXPECT_DOUBLE_EQ(captured["noise_cm"].get<double>(), 0.3);
  EXPECT_LT(captured["methods"]["spline"]["garment_cm"].get<double>(), 2.0) << captured.dump(2);

  // The model from the first run serves another run at its spacing, and is refused at another.
  const CliRun reused = runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "all", "--spacing",
                                       "0.08", "--length-model", (out / "length_model.json").string(), "--out",
                                       (work_ / "reused").string(), "--quiet"});
  ASSERT_EQ(reused.status, 0) << reused;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(readFile(work_ / "reused" / "metrics.json"))["methods"]["spline"]["cage_cm"],
                   metrics["methods"]["spline"]["cage_cm"].get<double>());
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "all", "--length-model",
                                     (out / "length_model.json").string(), "--out", (work_ / "spacing").string()}),
                      {"length_model.json", "0.08 m apart"}));
  EXPECT_TRUE(filesUnder(work_ / "spacing").empty());
}

TEST_F(CliReconstructTest, MarkersFormRebuildsOneSampleFromItsMarkers) {
  const fs::path markers = work_ / "m.json", pose = work_ / "pose.json", obj = work_ / "tie.obj";
  CliRun run = runPixelcloth({"markers", "--dataset", data_.string(), "--sample", "1", "--pose-out", pose.string(),
                              "--out", markers.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json set = nlohmann::json::parse(readFile(markers));
  EXPECT_EQ(set["garment"], "necktie");
  EXPECT_GT(set["markers"].size(), 8u);
  run = runPixelcloth({"reconstruct", "--markers", markers.string(), "--pose", pose.string(), "--dressing",
                       (work_ / "dressing").string(), "--out", obj.string()});
  ASSERT_EQ(run.status, 0) << run;
  const core::Mesh rebuilt = core::readMesh(obj), truth = core::readMesh(work_ / "bent" / "tie_1.obj");
  ASSERT_EQ(rebuilt.numVertices(), truth.numVertices());
  EXPECT_LT((rebuilt.V - truth.V).rowwise().norm().mean(), 0.01);
  EXPECT_TRUE(rebuilt.hasUV());

  // With the length model a dataset run fitted (markers at the default spacing, as `markers` placed them).
  run = runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "all", "--meshes", "0", "--out",
                       (work_ / "fit").string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  const fs::path withModel = work_ / "tie_model.obj";
  run = runPixelcloth({"reconstruct", "--markers", markers.string(), "--pose", pose.string(), "--dressing",
                       (work_ / "dressing").string(), "--length-model", (work_ / "fit" / "length_model.json").string(),
                       "--out", withModel.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_LT((core::readMesh(withModel).V - truth.V).rowwise().norm().mean(), 0.01);
}

TEST_F(CliReconstructTest, WriteBaseFormWritesABaseFolderOfEveryRow) {
  const fs::path out = work_ / "bases";
  const CliRun run = runPixelcloth(
      {"reconstruct", "--dataset", data_.string(), "--write-base", out.string(), "--spacing", "0.08", "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(lines(run.out).size(), 1u) << run;
  EXPECT_NE(run.out.find(out.string()), std::string::npos) << run;
  EXPECT_NE(run.out.find("3 samples"), std::string::npos) << run;
  EXPECT_TRUE(run.err.empty()) << run;
  EXPECT_TRUE(noTemporaries(out));
  const data::BaseSet base = data::openBaseSet(out, data::readDatasetInfo(data_));
  EXPECT_EQ(base.samples, 3);
  EXPECT_EQ(base.vertices, tie_.mesh.numVertices());
  EXPECT_GT(base.markers, 8);
  EXPECT_TRUE(base.offsets.allFinite());
  EXPECT_GT(base.offsets.cwiseAbs().maxCoeff(), 0);
  EXPECT_DOUBLE_EQ(base.manifest["settings"]["marker_spacing_m"].get<double>(), 0.08);
  EXPECT_EQ(base.manifest["settings"]["method"], "spline_anisotropic");
}

TEST_F(CliReconstructTest, WriteBaseRefusesOptionsThatMeanNothingThere) {
  const std::string out = (work_ / "bases").string();
  EXPECT_TRUE(
      refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--write-base", out, "--split", "test"}),
              {"--split", "all splits"}));
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--write-base", out, "--out",
                                     (work_ / "rec").string()}),
                      {"--write-base", "--out"}));
  EXPECT_TRUE(
      refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--write-base", out, "--method", "linear"}),
              {"--method"}));
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--markers", (work_ / "m.json").string(), "--pose",
                                     (work_ / "p.json").string(), "--write-base", out}),
                      {"--write-base", "--dataset"}));
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string()}), {"--out", "--write-base"}));
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--write-base", data_.string()}),
                      {"dataset folder"}));
  EXPECT_TRUE(filesUnder(out).empty());
  EXPECT_FALSE(fs::exists(work_ / "rec"));
  EXPECT_EQ(runPixelcloth({"dataset", "check", data_.string()}).status, 0);
}

TEST_F(CliReconstructTest, RefusesBadInputsNamingTheFileAndWritesNothing) {
  const fs::path markers = work_ / "m.json", pose = work_ / "pose.json";
  ASSERT_EQ(runPixelcloth({"markers", "--dataset", data_.string(), "--sample", "0", "--pose-out", pose.string(),
                           "--out", markers.string()})
                .status,
            0);
  const std::string dressing = (work_ / "dressing").string();
  auto reconstruct = [&](const fs::path& m, const fs::path& out) {
    return runPixelcloth({"reconstruct", "--markers", m.string(), "--pose", pose.string(), "--dressing", dressing,
                          "--out", out.string()});
  };
  EXPECT_TRUE(refused(reconstruct(work_ / "missing.json", work_ / "a.obj"), {"missing.json"}));
  EXPECT_FALSE(fs::exists(work_ / "a.obj"));

  nlohmann::json set = nlohmann::json::parse(readFile(markers));
  nlohmann::json edited = set;
  for (auto& m : edited["markers"])
    if (m.contains("curve")) {
      m["curve"] = "collar";
      break;
    }
  writeFile(work_ / "curve.json", edited.dump());
  EXPECT_TRUE(refused(reconstruct(work_ / "curve.json", work_ / "b.obj"), {"curve.json", "collar"}));
  EXPECT_FALSE(fs::exists(work_ / "b.obj"));

  std::string text = set.dump();
  const size_t at = text.find("\"position\":[");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 12, "NaN,");
  writeFile(work_ / "nan.json", text);
  EXPECT_TRUE(refused(reconstruct(work_ / "nan.json", work_ / "c.obj"), {"nan.json"}));
  EXPECT_FALSE(fs::exists(work_ / "c.obj"));

  edited = set;
  edited["garment"] = "skirt";
  writeFile(work_ / "skirt.json", edited.dump());
  EXPECT_TRUE(refused(reconstruct(work_ / "skirt.json", work_ / "d.obj"), {"skirt.json", "skirt"}));
  EXPECT_FALSE(fs::exists(work_ / "d.obj"));

  // A length model that is cut short, or for another garment.
  auto withModel = [&](const fs::path& model, const fs::path& out) {
    return runPixelcloth({"reconstruct", "--markers", markers.string(), "--pose", pose.string(), "--dressing", dressing,
                          "--length-model", model.string(), "--out", out.string()});
  };
  writeFile(work_ / "cut_model.json", R"({"format": "pixelcloth.length_model", "garment": "necktie", "cur)");
  EXPECT_TRUE(refused(withModel(work_ / "cut_model.json", work_ / "f.obj"), {"cut_model.json"}));
  writeFile(work_ / "shirt_model.json",
            R"({"format": "pixelcloth.length_model", "garment": "tshirt", "marker_spacing_m": 0.1,
                "smoothing_passes": 2, "samples": 1, "curves": {"chest": {"intercept": 1, "slope": 0}}})");
  EXPECT_TRUE(refused(withModel(work_ / "shirt_model.json", work_ / "g.obj"), {"shirt_model.json", "tshirt"}));
  EXPECT_FALSE(fs::exists(work_ / "f.obj") || fs::exists(work_ / "g.obj"));

  // T-shirt markers for a necktie dressing: the embedding does not fit.
  ASSERT_EQ(runPixelcloth({"markers", "--garment", "tshirt", "--out", (work_ / "shirt_def.json").string()}).status, 0);
  EXPECT_TRUE(refused(reconstruct(work_ / "shirt_def.json", work_ / "e.obj"), {"shirt_def.json", "no position"}));
  EXPECT_FALSE(fs::exists(work_ / "e.obj"));

  // Dataset form: an unknown split, a folder that is not a dataset, a clearance of a metre.
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--body-clearance", "1", "--out",
                                     (work_ / "r3").string()}),
                      {"clearance"}));
  EXPECT_TRUE(filesUnder(work_ / "r3").empty());
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "validation", "--out",
                                     (work_ / "r1").string()}),
                      {"validation"}));
  EXPECT_TRUE(refused(
      runPixelcloth({"reconstruct", "--dataset", (work_ / "nowhere").string(), "--out", (work_ / "r2").string()}),
      {"nowhere"}));
  EXPECT_TRUE(filesUnder(work_ / "r1").empty());
  EXPECT_TRUE(filesUnder(work_ / "r2").empty());
}

// ---------------------------------------------------------------------------------------------------------------------
// The gaps a new user's bad inputs found

TEST_F(CliTest, NegativeSeedsAreRefusedInEveryVerb) {
  const fs::path work = dir("work");
  EXPECT_TRUE(refused(runPixelcloth({"pose", "--random", "1", "--seed", "-1", "--body", (work / "b").string(), "--out",
                                     (work / "p").string()}),
                      {"--seed", "a seed is a whole number of 0 or more, got -1"}));
  EXPECT_TRUE(refused(runPixelcloth({"generate", "--count", "2", "--seed", "-5", "--out", (work / "d").string()}),
                      {"--seed", "got -5"}));
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "import", "--garment", "necktie", "--objs", work.string(), "--poses",
                                     (work / "p.csv").string(), "--dressing", work.string(), "--seed", "-2", "--out",
                                     (work / "i").string()}),
                      {"--seed", "got -2"}));
  EXPECT_TRUE(filesUnder(work).empty()) << listing(filesUnder(work));
}

TEST_F(CliTest, ImagesRefusesNanInValuesAndInAnImage) {
  const fs::path work = dir("work");
  Eigen::MatrixXf x = shirtOffsets();
  x(10, 2) = std::numeric_limits<float>::quiet_NaN();
  core::writeNpy(work / "nan.npy", x);
  EXPECT_TRUE(refused(runPixelcloth({"images", "--garment", "tshirt", "--values", (work / "nan.npy").string(), "--out",
                                     (work / "img").string()}),
                      {"nan.npy", "row 11, column 3 (counting from 1) is nan"}));
  EXPECT_TRUE(filesUnder(work / "img").empty());

  core::writeNpy(work / "good.npy", shirtOffsets());
  ASSERT_EQ(runPixelcloth({"images", "--garment", "tshirt", "--values", (work / "good.npy").string(), "--out",
                           (work / "good").string()})
                .status,
            0);
  core::ExrImage exr = core::readExr(work / "good" / "cloth.exr");
  for (size_t c = 0; c < exr.channels.size(); ++c)
    if (exr.channelNames[c] == "back.dn") exr.channels[c](7, 20) = std::numeric_limits<float>::infinity();
  core::writeExr(work / "inf.exr", exr);
  EXPECT_TRUE(refused(runPixelcloth({"images", "--garment", "tshirt", "--image", (work / "inf.exr").string(), "--out",
                                     (work / "v.npy").string()}),
                      {"inf.exr", "channel 'back.dn' is inf at row 8, column 21"}));
  EXPECT_FALSE(fs::exists(work / "v.npy"));
}

TEST_F(CliBodyTest, ImportOfABodyInCentimetresSuggestsTheUnits) {
  const fs::path work = dir("work");
  core::Mesh mesh = core::readMesh(body_ / "body.obj");
  mesh.V *= 100;
  core::writeMesh(work / "cm.obj", mesh);
  nlohmann::json joints = jointsOf(body_);
  for (auto& [name, p] : joints["joints"].items())
    for (auto& c : p) c = c.get<double>() * 100;
  writeFile(work / "joints.json", joints.dump());
  EXPECT_TRUE(refused(runPixelcloth({"body", "--import", (work / "cm.obj").string(), "--joints",
                                     (work / "joints.json").string(), "--out", (work / "out").string()}),
                      {"cm.obj", "units tall", "expected 0.5 to 2.5 metres", "centimetres: scale it by 0.01"}));
  EXPECT_FALSE(fs::exists(work / "out"));
}

TEST_F(CliBodyTest, ImportOfABodyWithAnExtraShellNeedsLargestComponent) {
  const fs::path work = dir("work");
  core::Mesh mesh = core::readMesh(body_ / "body.obj");
  const int n = mesh.numVertices(), f = mesh.numFaces();
  mesh.V.conservativeResize(n + 4, 3);  // a small closed tetrahedron in front of the face: a separately modelled eye
  const Eigen::RowVector3d eye(0.03, mesh.V.col(1).maxCoeff() - 0.1, mesh.V.col(2).maxCoeff() + 0.02);
  mesh.V.bottomRows(4) << eye, eye + Eigen::RowVector3d(0.01, 0, 0), eye + Eigen::RowVector3d(0, 0.01, 0),
      eye + Eigen::RowVector3d(0, 0, 0.01);
  mesh.F.conservativeResize(f + 4, 3);
  mesh.F.bottomRows(4) << n, n + 2, n + 1, n, n + 1, n + 3, n, n + 3, n + 2, n + 1, n + 2, n + 3;
  core::writeMesh(work / "eyes.obj", mesh);
  writeFile(work / "joints.json", jointsOf(body_).dump());
  EXPECT_TRUE(refused(runPixelcloth({"body", "--import", (work / "eyes.obj").string(), "--joints",
                                     (work / "joints.json").string(), "--out", (work / "out").string()}),
                      {"eyes.obj", "is closed but has 2 components", "--largest-component"}));
  EXPECT_FALSE(fs::exists(work / "out"));
  const CliRun run = runPixelcloth({"body", "--import", (work / "eyes.obj").string(), "--joints",
                                    (work / "joints.json").string(), "--largest-component", "--out",
                                    (work / "out").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_NE(run.err.find("warning: " + (work / "eyes.obj").string() + ": kept the largest of 2 components"),
            std::string::npos)
      << run;
  EXPECT_EQ(core::readMesh(work / "out" / "body.obj").numVertices(), n);
}

TEST_F(CliBodyTest, PoseBeyondTheJointLimitsIsRefusedOrClamped) {
  const fs::path work = dir("work");
  writeFile(work / "twist.json", R"({"joints": {"neck": {"euler_deg": [0, 80, 0]}}})");
  EXPECT_TRUE(refused(runPixelcloth({"pose", "--body", body_.string(), "--pose", (work / "twist.json").string(),
                                     "--out", (work / "out").string()}),
                      {"twist.json", "joint 'neck'", "beyond its limits -60 to 60", "--clamp-to-limits"}));
  EXPECT_TRUE(filesUnder(work / "out").empty());
  const CliRun run = runPixelcloth({"--clamp-to-limits", "pose", "--body", body_.string(), "--pose",
                                    (work / "twist.json").string(), "--out", (work / "out").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_NE(run.err.find("clamped into the limits"), std::string::npos) << run;
}

TEST_F(CliBodyTest, DressGivenADatasetFolderPointsAtItsBodyFolder) {
  const fs::path work = dir("work");
  fs::create_directories(work / "data");
  fs::copy(body_, work / "data" / "body", fs::copy_options::recursive);
  EXPECT_TRUE(refused(runPixelcloth({"dress", "--body", (work / "data").string(), "--out", (work / "out").string()}),
                      {"is not a body folder but holds one", (work / "data" / "body").string()}));
  EXPECT_TRUE(filesUnder(work / "out").empty());
}

TEST_F(CliDatasetTest, DatasetFilesAreVerifiedWhenOpenedUnlessNoVerify) {
  const fs::path data = work_ / "data";
  ASSERT_EQ(import(work_ / "objs", work_ / "poses.csv", data).status, 0);
  fs::copy(data, work_ / "damaged", fs::copy_options::recursive);
  std::string bytes = readFile(data / "positions.npy");
  bytes[bytes.size() - 5] ^= 0x40;
  writeFile(work_ / "damaged" / "positions.npy", bytes);
  EXPECT_TRUE(refused(runPixelcloth({"images", "--dataset", (work_ / "damaged").string(), "--samples", "0", "--out",
                                     (work_ / "images").string()}),
                      {"positions.npy", "CRC-32", "--no-verify"}));
  EXPECT_TRUE(filesUnder(work_ / "images").empty());
  const CliRun run = runPixelcloth({"--no-verify", "images", "--dataset", (work_ / "damaged").string(), "--samples",
                                    "0", "--out", (work_ / "images").string(), "--quiet"});
  EXPECT_EQ(run.status, 0) << run;

  // A failed merge leaves neither its output folder nor a staging folder behind.
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "merge", "--out", (work_ / "merged").string(),
                                     (work_ / "damaged").string()}),
                      {"positions.npy", "CRC-32"}));
  EXPECT_FALSE(fs::exists(work_ / "merged"));
  for (const auto& entry : fs::directory_iterator(work_))
    EXPECT_EQ(entry.path().filename().string().find("merging"), std::string::npos) << entry.path();
}

TEST_F(CliReconstructTest, MarkersFarFromTheBodyOrOfAnotherGarmentAreRefused) {
  const fs::path markers = work_ / "m.json", pose = work_ / "pose.json";
  ASSERT_EQ(runPixelcloth({"markers", "--dataset", data_.string(), "--sample", "1", "--pose-out", pose.string(),
                           "--out", markers.string()})
                .status,
            0);
  nlohmann::json set = nlohmann::json::parse(readFile(markers));
  const std::string name = set["markers"][2]["name"];
  set["markers"][2]["position"] = {1e30, 0, 0};
  writeFile(work_ / "far.json", set.dump());
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--markers", (work_ / "far.json").string(), "--pose",
                                     pose.string(), "--dressing", (work_ / "dressing").string(), "--out",
                                     (work_ / "far.obj").string()}),
                      {"far.json", "marker '" + name + "' is 1e+30 m from where its garment vertex rests",
                       "expected within 1 m"}));
  EXPECT_FALSE(fs::exists(work_ / "far.obj"));

  // The necktie's markers with a T-shirt's dressing folder.
  const fs::path shirtDressing = work_ / "shirt_dressing";
  fs::create_directories(shirtDressing);
  fs::copy(body_, shirtDressing / "body", fs::copy_options::recursive);
  const core::Mesh body = core::readMesh(body_ / "body.obj");
  const garment::Garment shirt = garment::makeTShirt();
  const Eigen::MatrixX3d u = Eigen::RowVector3d(1, 0, 0).replicate(shirt.mesh.numVertices(), 1);
  garment::saveEmbedding(shirtDressing, garment::embedClosest(body.V, body.F, shirt.mesh.V, u));
  core::writeNpy(shirtDressing / "rest_positions.npy", Eigen::MatrixXd(shirt.mesh.V));
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--markers", markers.string(), "--pose", pose.string(),
                                     "--dressing", shirtDressing.string(), "--out", (work_ / "mixed.obj").string()}),
                      {"rest_positions.npy", "m.json", "necktie", "the garments differ"}));
  EXPECT_FALSE(fs::exists(work_ / "mixed.obj"));
}

}  // namespace
}  // namespace pixelcloth::apps
