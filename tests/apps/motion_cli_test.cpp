// pixelcloth motion import and pose --motion: a CMU-style BVH (tests/assets/motion/cmu_style.bvh: the CMU conversions'
// names, hierarchy, channel order and 120 fps; a frame with the forearm bent beyond its limits, as real capture has)
// retargeted to the body, posed frame by frame, and the files read back by numpy.
#include "cli_fixtures.h"
#include "pixelcloth/body/skeleton.h"
#include "support/python.h"

namespace pixelcloth::apps {

namespace {
fs::path clip() { return pixelcloth::testing::asset("motion/cmu_style.bvh"); }
}  // namespace

TEST_F(CliBodyTest, MotionImportRefusesAFrameBeyondTheLimitsAndClampsItWhenAsked) {
  const fs::path out = dir("out") / "motion";
  EXPECT_TRUE(
      refused(runPixelcloth({"motion", "import", clip().string(), "--body", body_.string(), "--out", out.string()}),
              {"cmu_style.bvh: frame 3", "l_forearm", "--clamp-to-limits"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));

  const CliRun run = runPixelcloth(
      {"--clamp-to-limits", "motion", "import", clip().string(), "--body", body_.string(), "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_NE(run.out.find("4 frames at 120"), std::string::npos) << run;
  EXPECT_NE(run.out.find("cmu joint map, 1 frames clamped"), std::string::npos) << run;
  for (const char* name : {"motion.json", "poses.npy"}) EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  EXPECT_TRUE(isPng(out / "motion.png"));
  EXPECT_TRUE(noTemporaries(out));
  const nlohmann::json motion = nlohmann::json::parse(readFile(out / "motion.json"));
  EXPECT_EQ(motion["frames"], 4);
  EXPECT_NEAR(motion["fps"].get<double>(), 120.0, 0.1);
  EXPECT_EQ(motion["joint_map"]["name"], "cmu");
  EXPECT_EQ(motion["joint_map"]["joints"]["l_forearm"], "LeftForeArm");
  EXPECT_EQ(motion["clamped_frames"], 1);
  // The root's turn (30 degrees at frame 1) and walk are kept for export, not put into the pose.
  const nlohmann::json& root = motion["root"];
  EXPECT_NEAR(root["rotation"][1][0].get<double>(), std::cos(30 * M_PI / 180), 1e-3);
  EXPECT_GT(root["translation_m"][3][2].get<double>(), 0.1);

  // The clip's joint angles, in ours: frame 1 lowers the left arm 45 degrees (-z), bends the forearm 60 (-y) and the
  // spine 10 (x), all relative to a root that has turned.
  const Eigen::MatrixXf poses = core::readNpyMatrixF(out / "poses.npy", 4, 90);
  const Eigen::Matrix<double, 10, 3> frame1 = body::Pose::fromVector(poses.row(1).transpose()).toEulerDegrees();
  EXPECT_NEAR(frame1(5, 2), -45, 3) << frame1;  // l_arm z
  EXPECT_NEAR(frame1(6, 1), -60, 3) << frame1;  // l_forearm y
  EXPECT_NEAR(frame1(1, 0), 10, 3) << frame1;   // spine x
  EXPECT_NEAR(frame1(0, 1), 0, 1) << frame1;    // lower_back y: the root's turn is not in the pose
  const Eigen::Matrix<double, 10, 3> frame3 = body::Pose::fromVector(poses.row(3).transpose()).toEulerDegrees();
  EXPECT_NEAR(frame3(6, 2), 0, 1e-3) << frame3;  // clamped

  if (!pixelcloth::testing::numpyPython().empty()) {
    const std::string checked = pixelcloth::testing::runPython(
        "import sys, numpy as np\n"
        "p = np.load(sys.argv[1] + '/poses.npy')\n"
        "assert p.dtype == np.float32 and p.shape == (4, 90), (p.dtype, p.shape)\n"
        "r = p.reshape(4, 10, 3, 3).astype(np.float64)\n"
        "err = np.abs(np.einsum('fkij,fkil->fkjl', r, r) - np.eye(3)).max()\n"
        "assert err < 1e-5, err\n"
        "print('ok')\n",
        out);
    EXPECT_EQ(checked, "ok\n");
  }

  // Every frame posed, and the poses.json that writes read back by pose --pose.
  const fs::path posed = dir("posed");
  const CliRun pose =
      runPixelcloth({"pose", "--body", body_.string(), "--motion", out.string(), "--out", (posed / "a").string()});
  ASSERT_EQ(pose.status, 0) << pose;
  for (const char* name : {"posed_000.obj", "posed_003.obj", "poses.json", "posed.png"})
    EXPECT_TRUE(fs::is_regular_file(posed / "a" / name)) << name;
  const CliRun again = runPixelcloth({"pose", "--body", body_.string(), "--pose", (posed / "a" / "poses.json").string(),
                                      "--out", (posed / "b").string()});
  ASSERT_EQ(again.status, 0) << again;
  const core::Mesh a = core::readMesh(posed / "a" / "posed_002.obj"), b = core::readMesh(posed / "b" / "posed_002.obj");
  ASSERT_EQ(a.numVertices(), b.numVertices());
  EXPECT_LT((a.V - b.V).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_FALSE(fs::exists(posed / "b" / "posed_004.obj"));
}

TEST_F(CliBodyTest, MotionImportRefusesBadClipsAndMapsNamingThem) {
  const fs::path work = dir("work"), out = work / "motion";
  const std::string text = readFile(clip());
  writeFile(work / "truncated.bvh", text.substr(0, text.size() / 2));
  EXPECT_TRUE(refused(runPixelcloth({"motion", "import", (work / "truncated.bvh").string(), "--body", body_.string(),
                                     "--out", out.string()}),
                      {"truncated.bvh"}));
  writeFile(work / "clip.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(refused(runPixelcloth({"motion", "import", (work / "clip.obj").string(), "--body", body_.string(),
                                     "--out", out.string()}),
                      {"clip.obj", "no animation"}));
  EXPECT_TRUE(refused(runPixelcloth({"motion", "import", (work / "none.bvh").string(), "--out", out.string()}),
                      {"none.bvh", "no such motion clip"}));
  writeFile(work / "map.json", R"({"root": "Hips", "l_arm": "LeftUpperArm"})");
  EXPECT_TRUE(refused(runPixelcloth({"--clamp-to-limits", "motion", "import", clip().string(), "--map",
                                     (work / "map.json").string(), "--body", body_.string(), "--out", out.string()}),
                      {"map.json", "no joint 'LeftUpperArm'", "LeftForeArm"}));
  EXPECT_TRUE(refused(
      runPixelcloth({"pose", "--body", body_.string(), "--motion", work.string(), "--out", (work / "posed").string()}),
      {"no motion.json", "motion import"}));
  EXPECT_TRUE(filesUnder(out).empty()) << listing(filesUnder(out));
  EXPECT_FALSE(fs::exists(work / "posed"));
}

}  // namespace pixelcloth::apps
