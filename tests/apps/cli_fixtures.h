#pragma once

// What the command-line tests share: helpers on files and output, the body folder built once for every test process,
// and the fixtures (a test folder of its own; a body; a necktie dataset to import; a dataset to reconstruct).
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
#include "support/cli.h"
#include "support/test_util.h"

namespace pixelcloth::apps {

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
inline const std::vector<std::string> kPoseJointNames = {"lower_back", "spine",     "spine1",     "neck",  "l_shoulder",
                                                         "l_arm",      "l_forearm", "r_shoulder", "r_arm", "r_forearm"};

// ---------------------------------------------------------------------------------------------------------------------
// Running commands

// ---------------------------------------------------------------------------------------------------------------------
// Files

inline std::string listing(const std::vector<std::string>& files) {
  std::string text;
  for (const auto& f : files) text += "\n  " + f;
  return text.empty() ? " (none)" : text;
}

/// No temporary `NAME.tmp-PID` left by an atomic write anywhere under `dir`.
inline ::testing::AssertionResult noTemporaries(const fs::path& dir) {
  for (const std::string& file : filesUnder(dir)) {
    if (file.find(".tmp-") != std::string::npos)
      return ::testing::AssertionFailure() << dir << " holds a half-written file: " << file;
  }
  return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult isPng(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return ::testing::AssertionFailure() << path << " does not exist";
  std::string head = readFile(path).substr(0, 8);
  if (head != std::string("\x89PNG\r\n\x1a\n", 8))
    return ::testing::AssertionFailure() << path << " does not start with the PNG signature";
  return ::testing::AssertionSuccess();
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

inline std::string joinLines(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += line + "\n";
  return text;
}

inline bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

/// A Python 3 interpreter with NumPy ("" when none): the system one first (a pyenv `python3` may lack NumPy).
inline std::string pythonWithNumpy() {
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

inline const SharedBody& sharedBody() {
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
inline nlohmann::json jointsOf(const fs::path& bodyFolder) {
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

}  // namespace pixelcloth::apps
