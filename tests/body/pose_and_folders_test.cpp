// Body folders on disk and pose JSON: round trips and the errors users will meet.
#include <gtest/gtest.h>

#include <fstream>

#include "pixelcloth/body/body.h"
#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/npy.h"
#include "support/body_fixtures.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace pb = pixelcloth::body;
namespace fs = std::filesystem;

using pixelcloth::testing::coarseMannequin;

namespace {

void expectError(const std::function<void()>& call, const std::vector<std::string>& parts) {
  std::string message = pixelcloth::testing::inputErrorOf(call);
  for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
}
}  // namespace

TEST(BodyFolder, SaveThenLoadGivesTheSameBody) {
  fs::path dir = pixelcloth::testing::freshDir("body");
  const pb::Body& body = coarseMannequin();
  pb::saveBody(dir, body, "test");
  for (const char* name : {"body.obj", "skeleton.json", "weights.npy", "parts.json"})
    EXPECT_TRUE(fs::exists(dir / name));
  pb::Body loaded = pb::loadBody(dir);
  EXPECT_EQ(loaded.mesh.F, body.mesh.F);
  EXPECT_LT((loaded.mesh.V - body.mesh.V).cwiseAbs().maxCoeff(), 1e-6);  // OBJ stores floats
  EXPECT_LT((loaded.weights - body.weights).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(loaded.skeleton.names, body.skeleton.names);
  EXPECT_EQ(loaded.skeleton.parents, body.skeleton.parents);
  EXPECT_LT((loaded.skeleton.positions - body.skeleton.positions).cwiseAbs().maxCoeff(), 1e-12);
  ASSERT_EQ(loaded.parts.size(), 3u);
  EXPECT_EQ(loaded.parts[2].faces, body.parts[2].faces);
  // Same pose, same posed mesh.
  pb::Pose pose = pb::randomPose(5);
  EXPECT_LT((loaded.posedVertices(pose) - body.posedVertices(pose)).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(BodyFolder, WeightsForAnotherMeshAreRefused) {
  fs::path dir = pixelcloth::testing::freshDir("body");
  pb::saveBody(dir, coarseMannequin(), "test");
  pc::writeNpy(dir / "weights.npy", Eigen::MatrixXf(Eigen::MatrixXf::Constant(100, 12, 1.0f / 12)));
  expectError([&] { pb::loadBody(dir); }, {"weights.npy", "100", std::to_string(coarseMannequin().mesh.numVertices())});
}

TEST(BodyFolder, BrokenFilesAreNamed) {
  fs::path dir = pixelcloth::testing::freshDir("body");
  pb::saveBody(dir, coarseMannequin(), "test");
  expectError([&] { pb::loadBody(dir / "nope"); }, {"nope", "no such body folder"});

  std::string skeleton = pc::readTextFile(dir / "skeleton.json");
  pc::writeTextAtomically(dir / "skeleton.json", skeleton.substr(0, skeleton.size() / 2));
  expectError([&] { pb::loadBody(dir); }, {"skeleton.json"});
  pc::writeTextAtomically(dir / "skeleton.json", skeleton);

  nlohmann::json parts = pc::readJson(dir / "parts.json");
  parts["parts"][0]["faces"].push_back(10000000);
  pc::writeJson(dir / "parts.json", parts);
  expectError([&] { pb::loadBody(dir); }, {"left_arm", "10000000"});

  // Weights that do not sum to one.
  pb::saveBody(dir, coarseMannequin(), "test");
  Eigen::MatrixXf w = coarseMannequin().weights.cast<float>();
  w(7, 0) += 0.5f;
  pc::writeNpy(dir / "weights.npy", w);
  expectError([&] { pb::loadBody(dir); }, {"vertex 8", "sum"});  // row 7 counted from 1
}

TEST(PoseJson, BothFormsAndTheRoundTrip) {
  fs::path dir = pixelcloth::testing::freshDir("pose");
  pb::Pose pose = pb::randomPose(11);
  pc::writeJson(dir / "full.json", pb::poseToJson(pose));
  pb::Pose back = pb::readPose(dir / "full.json");
  for (int k = 0; k < 10; ++k) EXPECT_LT((back.rotations[k] - pose.rotations[k]).norm(), 1e-6);

  pc::writeJson(dir / "euler.json", {{"joints", {{"l_arm", {{"euler_deg", {0, 0, -60}}}}}}});
  pb::Pose euler = pb::readPose(dir / "euler.json");
  EXPECT_LT((euler.rotations[5] - pb::rotationFromEulerXZY(Eigen::Vector3d(0, 0, -60))).norm(), 1e-6);
  EXPECT_LT((euler.rotations[0] - Eigen::Matrix3d::Identity()).norm(), 1e-12);
}

TEST(PoseJson, MistakesAreNamed) {
  fs::path dir = pixelcloth::testing::freshDir("pose");
  auto write = [&](const std::string& name, const nlohmann::json& json) {
    pc::writeJson(dir / name, json);
    return dir / name;
  };
  expectError(
      [&] {
        pb::readPose(write("unknown.json", {{"joints", {{"l_elbow", {{"euler_deg", {0, 0, 0}}}}}}}));
      },
      {"unknown.json", "unknown joint 'l_elbow'"});
  expectError(
      [&] {
        pb::readPose(write("short.json", {{"pose", std::vector<float>(89, 0.0f)}}));
      },
      {"short.json", "90", "89"});
  expectError(
      [&] {
        pb::readPose(write("scaled.json", {{"pose", std::vector<float>(90, 2.0f)}}));
      },
      {"scaled.json", "not a rotation"});
  expectError([&] { pb::readPose(write("neither.json", {{"angles", 3}})); }, {"neither.json", "'pose'"});
  expectError([&] { pb::readPose(dir / "missing.json"); }, {"missing.json"});
}

TEST(PoseJson, AnglesBeyondTheJointLimitsAreRefusedOrClamped) {
  fs::path dir = pixelcloth::testing::freshDir("pose");
  // The neck turns at most 60 degrees (AAOS); 80 is beyond.
  pc::writeJson(dir / "twisted.json", {{"joints", {{"neck", {{"euler_deg", {0, 80, 0}}}}}}});
  expectError([&] { pb::readPose(dir / "twisted.json"); },
              {"twisted.json", "joint 'neck'", "y = 80", "beyond its limits -60 to 60", "--clamp-to-limits"});
  const pb::Pose clamped = pb::readPose(dir / "twisted.json", pb::BeyondLimits::Clamp);
  EXPECT_TRUE(clamped.withinLimits(1e-6));
  EXPECT_NEAR(clamped.toEulerDegrees()(3, 1), 60, 1e-6);
  // A pose at its limits exactly, as the sampler draws them, reads as it is.
  pc::writeJson(dir / "edge.json", {{"joints", {{"neck", {{"euler_deg", {0, 60, 0}}}}}}});
  EXPECT_NEAR(pb::readPose(dir / "edge.json").toEulerDegrees()(3, 1), 60, 1e-4);
}
