// pixelcloth body and pose: the mannequin, imported bodies and posed meshes; bad bodies, joints and poses refused.
#include "cli_fixtures.h"

namespace pixelcloth::apps {
namespace {

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

// The used-folder rule (core::checkRunFolder): no verb writes into a folder that holds another kind of run; the same
// kind again is fine.
TEST_F(CliTest, WritingIntoAFolderOfAnotherKindStopsBeforeAnythingIsWritten) {
  const fs::path work = dir("kinds"), body = work / "body", shirt = work / "shirt";
  ASSERT_EQ(runPixelcloth({"body", "--out", body.string()}).status, 0);
  ASSERT_EQ(runPixelcloth({"garment", "tshirt", "--out", shirt.string()}).status, 0);
  const std::vector<std::string> bodyFiles = filesUnder(body), shirtFiles = filesUnder(shirt);
  EXPECT_TRUE(refused(runPixelcloth({"garment", "tshirt", "--out", body.string()}),
                      {body.string(), "holds a body (skeleton.json); a garment goes in a folder of its own"}));
  EXPECT_TRUE(refused(runPixelcloth({"body", "--out", shirt.string()}), {"holds a garment (garment.json)"}));
  EXPECT_TRUE(
      refused(runPixelcloth({"dress", "--garment", "tshirt", "--out", body.string()}), {"holds a body", "a dressing"}));
  EXPECT_TRUE(
      refused(runPixelcloth({"cage", "--garment", "tshirt", "--out", shirt.string()}), {"holds a garment", "a cage"}));
  // Every verb that writes a folder follows the rule, the demo (which clears its subfolders) included.
  EXPECT_TRUE(refused(runPixelcloth({"demo", "--out", body.string()}), {"holds a body", "a demo report"}));
  EXPECT_TRUE(refused(runPixelcloth({"pose", "--body", body.string(), "--random", "2", "--out", shirt.string()}),
                      {"holds a garment", "posed bodies"}));
  EXPECT_TRUE(refused(runPixelcloth({"bases", "--figures", body.string()}), {"holds a body", "the basis figures"}));
  EXPECT_TRUE(refused(runPixelcloth({"experiments", "--out", shirt.string()}), {"holds a garment", "an experiments"}));
  EXPECT_TRUE(refused(runPixelcloth({"motion", "import", (work / "walk.bvh").string(), "--out", body.string()}),
                      {"holds a body", "a motion"}));
  EXPECT_TRUE(refused(runPixelcloth({"images", "--garment", "tshirt", "--values", (work / "offsets.npy").string(),
                                     "--out", body.string()}),
                      {"holds a body", "a cloth image"}));
  EXPECT_TRUE(refused(runPixelcloth({"view", shirt.string(), "--out", body.string()}), {"holds a body", "a viewer"}));
  EXPECT_TRUE(
      refused(runPixelcloth({"reconstruct", "--dataset", (work / "data").string(), "--write-base", shirt.string()}),
              {"holds a garment", "a base folder"}));
  EXPECT_TRUE(
      refused(runPixelcloth({"generate", "--count", "2", "--out", body.string()}), {"holds a body", "a dataset"}));
  EXPECT_EQ(filesUnder(body), bodyFiles);
  EXPECT_EQ(filesUnder(shirt), shirtFiles);
  EXPECT_EQ(runPixelcloth({"garment", "tshirt", "--out", shirt.string()}).status, 0);  // the same kind again
}

TEST_F(CliTest, BodyImportNamesMissingMesh) {
  fs::path work = dir("work");
  fs::path joints = work / "j.json";
  nlohmann::json positions = nlohmann::json::object();
  double height = 0.9;  // each joint at its own place: the joints file is fine, the mesh is missing
  for (const auto& name : kPoseJointNames) positions[name] = {0.0, height += 0.05, 0.0};
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
  const CliRun run =
      runPixelcloth({"body", "--import", (work / "eyes.obj").string(), "--joints", (work / "joints.json").string(),
                     "--largest-component", "--out", (work / "out").string()});
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

}  // namespace
}  // namespace pixelcloth::apps
