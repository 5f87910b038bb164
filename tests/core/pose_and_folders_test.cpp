// Body and garment folders on disk, and pose JSON: round trips and the errors users will meet.
#include <gtest/gtest.h>

#include <fstream>

#include "fixtures.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/body.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/garment.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/core/pose_io.h"
#include "test_util.h"

namespace pc = pixelcloth::core;
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
  const pc::Body& body = coarseMannequin();
  pc::saveBody(dir, body, "test");
  for (const char* name : {"body.obj", "skeleton.json", "weights.npy", "parts.json"})
    EXPECT_TRUE(fs::exists(dir / name));
  pc::Body loaded = pc::loadBody(dir);
  EXPECT_EQ(loaded.mesh.F, body.mesh.F);
  EXPECT_LT((loaded.mesh.V - body.mesh.V).cwiseAbs().maxCoeff(), 1e-6);  // OBJ stores floats
  EXPECT_LT((loaded.weights - body.weights).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(loaded.skeleton.names, body.skeleton.names);
  EXPECT_EQ(loaded.skeleton.parents, body.skeleton.parents);
  EXPECT_LT((loaded.skeleton.positions - body.skeleton.positions).cwiseAbs().maxCoeff(), 1e-12);
  ASSERT_EQ(loaded.parts.size(), 3u);
  EXPECT_EQ(loaded.parts[2].faces, body.parts[2].faces);
  // Same pose, same posed mesh.
  pc::Pose pose = pc::randomPose(5);
  EXPECT_LT((loaded.posedVertices(pose) - body.posedVertices(pose)).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(BodyFolder, WeightsForAnotherMeshAreRefused) {
  fs::path dir = pixelcloth::testing::freshDir("body");
  pc::saveBody(dir, coarseMannequin(), "test");
  pc::writeNpy(dir / "weights.npy", Eigen::MatrixXf(Eigen::MatrixXf::Constant(100, 12, 1.0f / 12)));
  expectError([&] { pc::loadBody(dir); }, {"weights.npy", "100", std::to_string(coarseMannequin().mesh.numVertices())});
}

TEST(BodyFolder, BrokenFilesAreNamed) {
  fs::path dir = pixelcloth::testing::freshDir("body");
  pc::saveBody(dir, coarseMannequin(), "test");
  expectError([&] { pc::loadBody(dir / "nope"); }, {"nope", "no such body folder"});

  std::string skeleton = pc::readTextFile(dir / "skeleton.json");
  pc::writeTextAtomically(dir / "skeleton.json", skeleton.substr(0, skeleton.size() / 2));
  expectError([&] { pc::loadBody(dir); }, {"skeleton.json"});
  pc::writeTextAtomically(dir / "skeleton.json", skeleton);

  nlohmann::json parts = pc::readJson(dir / "parts.json");
  parts["parts"][0]["faces"].push_back(10000000);
  pc::writeJson(dir / "parts.json", parts);
  expectError([&] { pc::loadBody(dir); }, {"left_arm", "10000000"});

  // Weights that do not sum to one.
  pc::saveBody(dir, coarseMannequin(), "test");
  Eigen::MatrixXf w = coarseMannequin().weights.cast<float>();
  w(7, 0) += 0.5f;
  pc::writeNpy(dir / "weights.npy", w);
  expectError([&] { pc::loadBody(dir); }, {"vertex 7", "sum"});
}

TEST(GarmentFolder, ObjKeepsUvsAndJsonDescribesSeams) {
  fs::path dir = pixelcloth::testing::freshDir("garment");
  pc::Garment shirt = pc::makeTShirt();
  pc::saveGarment(dir, shirt);
  pc::Mesh mesh = pc::readMesh(dir / "garment.obj");
  EXPECT_EQ(mesh.F, shirt.mesh.F);
  ASSERT_TRUE(mesh.hasUV());
  for (int f = 0; f < mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      ASSERT_LT((mesh.UV.row(mesh.FUV(f, k)) - shirt.mesh.UV.row(shirt.mesh.FUV(f, k))).norm(), 1e-6);
  nlohmann::json json = pc::readJson(dir / "garment.json");
  EXPECT_EQ(json["seams"].size(), shirt.seams.size());
  EXPECT_EQ(json["face_panel"].size(), static_cast<size_t>(mesh.numFaces()));
  EXPECT_EQ(json["layouts"][0]["name"], "front");
}

TEST(PoseJson, BothFormsAndTheRoundTrip) {
  fs::path dir = pixelcloth::testing::freshDir("pose");
  pc::Pose pose = pc::randomPose(11);
  pc::writeJson(dir / "full.json", pc::poseToJson(pose));
  pc::Pose back = pc::readPose(dir / "full.json");
  for (int k = 0; k < 10; ++k) EXPECT_LT((back.rotations[k] - pose.rotations[k]).norm(), 1e-6);

  pc::writeJson(dir / "euler.json", {{"joints", {{"l_arm", {{"euler_deg", {0, 0, -60}}}}}}});
  pc::Pose euler = pc::readPose(dir / "euler.json");
  EXPECT_LT((euler.rotations[5] - pc::rotationFromEulerXZY(Eigen::Vector3d(0, 0, -60))).norm(), 1e-6);
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
        pc::readPose(write("unknown.json", {{"joints", {{"l_elbow", {{"euler_deg", {0, 0, 0}}}}}}}));
      },
      {"unknown.json", "unknown joint 'l_elbow'"});
  expectError(
      [&] {
        pc::readPose(write("short.json", {{"pose", std::vector<float>(89, 0.0f)}}));
      },
      {"short.json", "90", "89"});
  expectError(
      [&] {
        pc::readPose(write("scaled.json", {{"pose", std::vector<float>(90, 2.0f)}}));
      },
      {"scaled.json", "not a rotation"});
  expectError([&] { pc::readPose(write("neither.json", {{"angles", 3}})); }, {"neither.json", "'pose'"});
  expectError([&] { pc::readPose(dir / "missing.json"); }, {"missing.json"});
}
