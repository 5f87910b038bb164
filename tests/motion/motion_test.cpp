// Motion clips in through assimp, retargeted to our skeleton. The clips are written here as users have them: BVH in
// other axes (Z up, turned), other units (inches), other channel orders, an A-pose rest, extra joints (legs, a second
// neck joint, hands), CMU and Mixamo naming; the retargeting is checked against the poses the clips were made from
// and by forward kinematics.
#include "pixelcloth/motion/motion.h"

#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/motion/glb.h"
#include "pixelcloth/motion/sequence.h"
#include "pixelcloth/motion/trajectories.h"
#include "support/body_fixtures.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
namespace pb = pixelcloth::body;
namespace pm = pixelcloth::motion;
using pixelcloth::testing::inputErrorOf;

namespace {

constexpr double kInch = 1 / 0.0254;  // clip units per metre

Eigen::Matrix3d axisRotation(int axis, double degrees) {
  return Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
}

/// One joint of a clip made from our skeleton.
struct ClipJoint {
  std::string name;
  int parent;                ///< index in the clip, -1 for the root
  Eigen::Vector3d restOurs;  ///< rest position in our axes, metres
  std::string channels;      ///< rotation channel order, e.g. "YXZ"
  int pose = -1;             ///< the pose joint it carries (kPoseJoints index), -1 none
};

/// A BVH of our skeleton in clip axes C (clip = C * ours), in inches, named by `names` (root, the 10 pose joints,
/// head, hands), with extra joints (legs, a second neck joint), and per frame the given poses and root motion.
/// `lowerArms`: the rest pose's arms lowered by that many degrees (an A-pose); the frames then carry the rotations
/// that put the bones where the poses put ours.
struct BvhClip {
  std::vector<ClipJoint> joints;
  Eigen::Matrix3d C;
  double lowerArms = 0;
  std::vector<pb::Pose> poses;
  std::vector<Eigen::Matrix3d> rootRotations;     ///< our axes
  std::vector<Eigen::Vector3d> rootTranslations;  ///< our axes, metres

  /// World rotation (clip axes) of every clip joint at frame f, and the rest bone correction of each.
  std::vector<Eigen::Matrix3d> globals(int f, const pb::Skeleton& skeleton) const {
    const pb::JointTransforms ours = pb::forwardKinematics(skeleton, poses[f]);
    std::vector<Eigen::Matrix3d> g(joints.size());
    for (size_t j = 0; j < joints.size(); ++j) {
      const ClipJoint& joint = joints[j];
      if (joint.parent < 0) {
        g[j] = C * rootRotations[f] * C.transpose();
        continue;
      }
      if (joint.pose < 0) {  // follows its parent
        g[j] = g[joint.parent];
        continue;
      }
      const int s = skeleton.index(pb::kPoseJoints[joint.pose]);
      // Our global rotation, undoing the rest pose's lowering of the arm bones: G_clip = G_ours * Q^-1.
      Eigen::Matrix3d q = Eigen::Matrix3d::Identity();
      const std::string& n = pb::kPoseJoints[joint.pose];
      if (n == "l_arm" || n == "l_forearm") q = axisRotation(2, -lowerArms);
      if (n == "r_arm" || n == "r_forearm") q = axisRotation(2, lowerArms);
      g[j] = C * rootRotations[f] * ours.rotations[s] * q.transpose() * C.transpose();
    }
    return g;
  }

  /// Rest positions in clip axes and units, with the arms lowered.
  std::vector<Eigen::Vector3d> restClip(const pb::Skeleton& skeleton) const {
    std::vector<Eigen::Vector3d> rest(joints.size());
    for (size_t j = 0; j < joints.size(); ++j) {
      Eigen::Vector3d p = joints[j].restOurs;
      // Lower every joint past a shoulder (the arm, forearm, hand) about the arm joint.
      for (const char* side : {"l", "r"}) {
        const Eigen::Vector3d pivot = skeleton.positions.row(skeleton.index(std::string(side) + "_arm")).transpose();
        const bool beyond = (side[0] == 'l' ? p.x() > pivot.x() + 1e-9 : p.x() < pivot.x() - 1e-9);
        if (beyond) p = pivot + axisRotation(2, side[0] == 'l' ? -lowerArms : lowerArms) * (p - pivot);
      }
      rest[j] = kInch * C * p;
    }
    return rest;
  }

  std::string text(const pb::Skeleton& skeleton) const {
    const std::vector<Eigen::Vector3d> rest = restClip(skeleton);
    std::ostringstream out;
    out << std::setprecision(10);
    std::function<void(int, int)> write = [&](int j, int depth) {
      const std::string pad(2 * depth, ' ');
      const ClipJoint& joint = joints[j];
      out << pad << (joint.parent < 0 ? "ROOT " : "JOINT ") << joint.name << "\n" << pad << "{\n";
      const Eigen::Vector3d offset = joint.parent < 0 ? rest[j] : Eigen::Vector3d(rest[j] - rest[joint.parent]);
      out << pad << "  OFFSET " << offset.x() << " " << offset.y() << " " << offset.z() << "\n";
      out << pad << "  CHANNELS " << (joint.parent < 0 ? "6 Xposition Yposition Zposition" : "3");
      for (char axis : joint.channels) out << " " << axis << "rotation";
      out << "\n";
      bool leaf = true;
      for (size_t c = 0; c < joints.size(); ++c)
        if (joints[c].parent == j) {
          write(static_cast<int>(c), depth + 1);
          leaf = false;
        }
      if (leaf)
        out << pad << "  End Site\n" << pad << "  {\n" << pad << "    OFFSET 0 " << 2.0 << " 0\n" << pad << "  }\n";
      out << pad << "}\n";
    };
    out << "HIERARCHY\n";
    write(0, 0);
    out << "MOTION\nFrames: " << poses.size() << "\nFrame Time: 0.0333333\n";
    for (size_t f = 0; f < poses.size(); ++f) {
      const std::vector<Eigen::Matrix3d> g = globals(static_cast<int>(f), skeleton);
      for (size_t j = 0; j < joints.size(); ++j) {
        if (joints[j].parent < 0) {
          const Eigen::Vector3d p = rest[j] + kInch * C * rootTranslations[f];
          out << p.x() << " " << p.y() << " " << p.z() << " ";
        }
        const Eigen::Matrix3d local =
            joints[j].parent < 0 ? g[j] : Eigen::Matrix3d(g[joints[j].parent].transpose() * g[j]);
        // BVH: R = R_first * R_second * R_third in channel order.
        const auto axis = [](char a) { return a == 'X' ? 0 : a == 'Y' ? 1 : 2; };
        const Eigen::Vector3d e =
            local.eulerAngles(axis(joints[j].channels[0]), axis(joints[j].channels[1]), axis(joints[j].channels[2])) *
            180 / M_PI;
        out << e.x() << " " << e.y() << " " << e.z() << " ";
      }
      out << "\n";
    }
    return out.str();
  }
};

/// Our skeleton as a clip named `names` (root, the 10 pose joints in kPoseJoints order, head, left hand, right hand).
BvhClip clipOf(const pb::Skeleton& s, const std::vector<std::string>& names, bool secondNeck) {
  BvhClip clip;
  auto pos = [&](const std::string& joint) { return Eigen::Vector3d(s.positions.row(s.index(joint)).transpose()); };
  auto& J = clip.joints;
  J.push_back({names[0], -1, pos("root"), "ZXY", -1});
  J.push_back({"LHipJoint", 0, pos("root") + Eigen::Vector3d(0.08, -0.05, 0), "YXZ", -1});  // legs: not ours
  J.push_back({"LeftUpLeg", 1, pos("root") + Eigen::Vector3d(0.09, -0.45, 0), "YXZ", -1});
  const std::vector<std::string> spine = {"lower_back", "spine", "spine1", "neck"};
  int parent = 0;
  for (int k = 0; k < 4; ++k) {
    J.push_back({names[1 + k], parent, pos(spine[k]), k % 2 ? "XZY" : "YXZ", k});
    parent = static_cast<int>(J.size()) - 1;
  }
  const int neck = parent, spine1 = neck - 1;
  if (secondNeck) {
    J.push_back({"Neck1", neck, 0.5 * (pos("neck") + pos("head")), "YXZ", -1});
    parent = static_cast<int>(J.size()) - 1;
  }
  J.push_back({names[11], parent, pos("head"), "YXZ", -1});
  for (int side = 0; side < 2; ++side) {
    parent = spine1;
    for (int k = 0; k < 3; ++k) {
      J.push_back({names[5 + 3 * side + k], parent, pos(pb::kPoseJoints[4 + 3 * side + k]), "ZYX", 4 + 3 * side + k});
      parent = static_cast<int>(J.size()) - 1;
    }
    const int forearm = s.index(side ? "r_forearm" : "l_forearm");
    J.push_back({names[12 + side], parent, Eigen::Vector3d(s.boneEnds.row(forearm).transpose()), "ZYX", -1});
  }
  return clip;
}

const std::vector<std::string> kCmuNames = {"Hips",         "LowerBack", "Spine",       "Spine1",        "Neck",
                                            "LeftShoulder", "LeftArm",   "LeftForeArm", "RightShoulder", "RightArm",
                                            "RightForeArm", "Head",      "LeftHand",    "RightHand"};
const std::vector<std::string> kMixamoNames = {
    "mixamorig:Hips",          "mixamorig:Spine",        "mixamorig:Spine1",       "mixamorig:Spine2",
    "mixamorig:Neck",          "mixamorig:LeftShoulder", "mixamorig:LeftArm",      "mixamorig:LeftForeArm",
    "mixamorig:RightShoulder", "mixamorig:RightArm",     "mixamorig:RightForeArm", "mixamorig:Head",
    "mixamorig:LeftHand",      "mixamorig:RightHand"};

fs::path writeClip(const fs::path& folder, const std::string& name, const std::string& text) {
  const fs::path path = folder / name;
  pixelcloth::core::writeTextAtomically(path, text);
  return path;
}

/// A clip of `frames` poses drawn within 80% of the limits, the root turning and walking.
BvhClip walkingClip(const pb::Skeleton& s, const std::vector<std::string>& names, int frames, bool secondNeck) {
  BvhClip clip = clipOf(s, names, secondNeck);
  for (int f = 0; f < frames; ++f) {
    clip.poses.push_back(pb::randomPose(100 + f, 0.8));
    clip.rootRotations.push_back(axisRotation(1, 25.0 * f) * axisRotation(0, 5.0 * f));
    clip.rootTranslations.push_back(Eigen::Vector3d(0.1 * f, 0.02 * f, -0.05 * f));
  }
  return clip;
}

double rotationDistance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return (a - b).cwiseAbs().maxCoeff(); }

}  // namespace

TEST(Motion, ACmuBvhInOtherAxesUnitsAndChannelOrdersComesBackAsThePosesItWasMadeFrom) {
  const pb::Skeleton skeleton = pb::mannequinSkeleton();
  BvhClip made = walkingClip(skeleton, kCmuNames, 6, true);
  made.C = axisRotation(0, 90) * axisRotation(1, 30);  // Z up, turned 30 degrees
  const fs::path dir = pixelcloth::testing::freshDir("motion_cmu");
  const pm::Clip clip = pm::readClip(writeClip(dir, "walk.bvh", made.text(skeleton)));
  EXPECT_EQ(clip.frames(), 6);
  EXPECT_NEAR(clip.fps, 30.0, 1e-3);
  const pm::JointMap map = pm::detectJointMap(clip);
  EXPECT_EQ(map.name, "cmu");
  const pm::Motion motion = pm::retarget(clip, skeleton, map);
  ASSERT_EQ(motion.frames(), 6);
  EXPECT_NEAR(motion.rootScale, 0.0254, 1e-6);  // inches
  for (int f = 0; f < motion.frames(); ++f) {
    SCOPED_TRACE(f);
    for (int k = 0; k < 10; ++k)
      EXPECT_LT(rotationDistance(motion.poses[f].rotations[k], made.poses[f].rotations[k]), 1e-4) << pb::kPoseJoints[k];
    EXPECT_LT(rotationDistance(motion.rootRotations[f], made.rootRotations[f]), 1e-4);
    EXPECT_LT((motion.rootTranslations.row(f).transpose() - made.rootTranslations[f]).norm(), 1e-5);
  }
}

TEST(Motion, AnAPoseMixamoClipPutsOurBonesWhereItsOwnAre) {
  const pb::Skeleton skeleton = pb::mannequinSkeleton();
  BvhClip made = walkingClip(skeleton, kMixamoNames, 4, false);
  made.C = axisRotation(1, -90);  // facing +X
  made.lowerArms = 40;
  const fs::path dir = pixelcloth::testing::freshDir("motion_mixamo");
  const pm::Clip clip = pm::readClip(writeClip(dir, "apose.bvh", made.text(skeleton)));
  const pm::JointMap map = pm::detectJointMap(clip);
  EXPECT_EQ(map.name, "mixamo");
  const pm::Motion motion = pm::retarget(clip, skeleton, map);
  // Forward kinematics on both sides: every bone of ours points as the clip's (root-relative, in our axes).
  const Eigen::Matrix3d A = made.C.transpose();
  for (int f = 0; f < motion.frames(); ++f) {
    const pb::JointTransforms ours = pb::forwardKinematics(skeleton, motion.poses[f]);
    const Eigen::Matrix3d rootInverse =
        (A * clip.rotations[f][clip.find("mixamorig:Hips")] * A.transpose()).transpose();
    for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
             {"l_arm", "l_forearm"}, {"r_arm", "r_forearm"}, {"spine", "spine1"}, {"l_shoulder", "l_arm"}}) {
      SCOPED_TRACE(from);
      const Eigen::Vector3d bone =
          (ours.positions.row(skeleton.index(to)) - ours.positions.row(skeleton.index(from))).normalized().transpose();
      const std::string a = map.joints.at(from), b = map.joints.at(to);
      const Eigen::Vector3d clipBone =
          rootInverse * A * (clip.positions[f].row(clip.find(b)) - clip.positions[f].row(clip.find(a))).transpose();
      EXPECT_GT(bone.dot(clipBone.normalized()), 1 - 1e-6);
    }
    // The rotations too, up to the twist about a bone that no bone direction fixes.
    for (int k = 0; k < 10; ++k)
      EXPECT_LT(rotationDistance(motion.poses[f].rotations[k], made.poses[f].rotations[k]), 0.02) << pb::kPoseJoints[k];
  }
}

TEST(Motion, FramesBeyondTheJointLimitsAreRefusedNamingTheFrameOrClampedAndCounted) {
  const pb::Skeleton skeleton = pb::mannequinSkeleton();
  BvhClip made = walkingClip(skeleton, kCmuNames, 3, true);
  made.C = Eigen::Matrix3d::Identity();
  // Frame 1: the left forearm bent 29 degrees about z, beyond its limit of 0 (real motion capture does this).
  Eigen::Matrix<double, 10, 3> degrees = Eigen::Matrix<double, 10, 3>::Zero();
  degrees(6, 2) = 29;
  made.poses[1] = pb::Pose::fromEulerDegrees(degrees);
  ASSERT_FALSE(made.poses[1].withinLimits());
  const fs::path dir = pixelcloth::testing::freshDir("motion_limits");
  const pm::Clip clip = pm::readClip(writeClip(dir, "beyond.bvh", made.text(skeleton)));
  const pm::JointMap map = pm::detectJointMap(clip);
  const std::string refused = inputErrorOf([&] { pm::retarget(clip, skeleton, map); });
  EXPECT_NE(refused.find("beyond.bvh: frame 1"), std::string::npos) << refused;
  EXPECT_NE(refused.find("l_forearm"), std::string::npos) << refused;
  EXPECT_NE(refused.find("--clamp-to-limits"), std::string::npos) << refused;
  const pm::Motion clamped = pm::retarget(clip, skeleton, map, pb::BeyondLimits::Clamp);
  EXPECT_EQ(clamped.clampedFrames, 1);
  for (const pb::Pose& pose : clamped.poses) EXPECT_TRUE(pose.withinLimits(1e-3));
}

TEST(Motion, AMotionFolderReadsBackAsItWasWritten) {
  const pb::Skeleton skeleton = pb::mannequinSkeleton();
  BvhClip made = walkingClip(skeleton, kCmuNames, 5, true);
  made.C = Eigen::Matrix3d::Identity();
  const fs::path dir = pixelcloth::testing::freshDir("motion_folder");
  const pm::Clip clip = pm::readClip(writeClip(dir, "walk.bvh", made.text(skeleton)));
  const pm::Motion motion = pm::retarget(clip, skeleton, pm::detectJointMap(clip));
  pm::writeMotion(dir / "m", motion);
  const pm::Motion back = pm::readMotion(dir / "m");
  ASSERT_EQ(back.frames(), 5);
  EXPECT_EQ(back.fps, motion.fps);
  EXPECT_EQ(back.map.joints, motion.map.joints);
  EXPECT_EQ(back.source, motion.source);
  for (int f = 0; f < 5; ++f) {
    for (int k = 0; k < 10; ++k)
      EXPECT_LT(rotationDistance(back.poses[f].rotations[k], motion.poses[f].rotations[k]), 1e-6);
    EXPECT_LT(rotationDistance(back.rootRotations[f], motion.rootRotations[f]), 1e-12);
    EXPECT_EQ(back.rootTranslations.row(f), motion.rootTranslations.row(f));
  }
  // A poses.npy of another frame count is refused naming it.
  pm::Motion shorter = motion;
  shorter.poses.resize(2);
  shorter.rootRotations.resize(2);
  shorter.rootTranslations.conservativeResize(2, 3);
  pm::writeMotion(dir / "short", shorter);
  fs::copy_file(dir / "short" / "poses.npy", dir / "m" / "poses.npy", fs::copy_options::overwrite_existing);
  EXPECT_NE(inputErrorOf([&] { pm::readMotion(dir / "m"); }).find("poses.npy"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { pm::readMotion(dir / "none"); }).find("no motion.json"), std::string::npos);
}

TEST(Motion, BadClipsAreRefusedNamingTheFile) {
  const pb::Skeleton skeleton = pb::mannequinSkeleton();
  BvhClip made = walkingClip(skeleton, kCmuNames, 3, true);
  made.C = Eigen::Matrix3d::Identity();
  const std::string good = made.text(skeleton);
  const fs::path dir = pixelcloth::testing::freshDir("motion_bad");
  auto errorOf = [&](const std::string& name, const std::string& text) {
    const fs::path path = writeClip(dir, name, text);
    return inputErrorOf([&] {
      const pm::Clip clip = pm::readClip(path);
      pm::retarget(clip, skeleton, pm::detectJointMap(clip));
    });
  };
  EXPECT_NE(inputErrorOf([&] { pm::readClip(dir / "missing.bvh"); }).find("missing.bvh: no such motion clip"),
            std::string::npos);
  const std::string truncated = errorOf("truncated.bvh", good.substr(0, good.size() * 2 / 3));
  EXPECT_NE(truncated.find("truncated.bvh"), std::string::npos) << truncated;
  const size_t frames = good.find("Frames: 3");
  ASSERT_NE(frames, std::string::npos);
  std::string none = good.substr(0, frames) + "Frames: 0\nFrame Time: 0.0333333\n";
  EXPECT_NE(errorOf("none.bvh", none).find("none.bvh"), std::string::npos);
  std::string fast = good;
  fast.replace(fast.find("Frame Time: 0.0333333"), 21, "Frame Time: 0.0000001");
  EXPECT_NE(errorOf("fast.bvh", fast).find("expected 1 to 1000"), std::string::npos);
  std::string nan = good;
  const size_t motionStart = nan.find("Frame Time");
  const size_t value = nan.find(' ', nan.find('\n', motionStart) + 1);  // the second number of frame 0
  nan.replace(value + 1, nan.find(' ', value + 1) - value - 1, "nan");
  EXPECT_NE(errorOf("nan.bvh", nan).find("not finite"), std::string::npos) << errorOf("nan.bvh", nan);
  std::string renamed = good;
  for (const char* from : {"LeftArm", "RightArm"})
    for (size_t at = renamed.find(from); at != std::string::npos; at = renamed.find(from, at + 1))
      renamed.replace(at, std::string(from).size(), std::string(from) == "LeftArm" ? "L_UpperArm" : "R_UpperArm");
  const std::string unknown = errorOf("renamed.bvh", renamed);
  EXPECT_NE(unknown.find("match none of the built-in joint maps"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("L_UpperArm"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("--map"), std::string::npos) << unknown;
  EXPECT_NE(errorOf("garbage.bvh", "HIERARCHY\nROOT {\n").find("garbage.bvh"), std::string::npos);
  // What assimp's reader would throw on part way (leaking the joints it has built) is refused before it, by line.
  const std::string cut = errorOf("cut.bvh", good.substr(0, good.size() - 40));
  EXPECT_NE(cut.find("cut.bvh, line"), std::string::npos) << cut;
  EXPECT_NE(cut.find("the file is truncated"), std::string::npos) << cut;
  std::string deep = "HIERARCHY\nROOT Hips\n{\n";
  for (int k = 0; k < 100000; ++k) deep += "JOINT j" + std::to_string(k) + " {\n";
  EXPECT_NE(errorOf("deep.bvh", deep).find("nested more than 256 deep"), std::string::npos);
  std::string huge = good;
  huge.replace(huge.find("OFFSET ") + 7, 1, "123456789012345678901234");
  EXPECT_NE(errorOf("huge.bvh", huge).find("expected an OFFSET coordinate, found '123456789012345678901234"),
            std::string::npos)
      << errorOf("huge.bvh", huge);
  std::string channel = good;
  channel.replace(channel.find("Xrotation"), 9, "Wrotation");
  EXPECT_NE(errorOf("channel.bvh", channel).find("found 'Wrotation'"), std::string::npos);
  EXPECT_NE(errorOf("nomotion.bvh", good.substr(0, good.find("MOTION"))).find("expected 'MOTION'"), std::string::npos);

  // A map file for the renamed clip works; one naming a joint the clip lacks is refused.
  const pm::Clip renamedClip = pm::readClip(dir / "renamed.bvh");
  nlohmann::json map;
  for (size_t k = 0; k < pm::mappedJoints().size(); ++k) map[pm::mappedJoints()[k]] = kCmuNames[k];
  map["l_arm"] = "L_UpperArm";
  map["r_arm"] = "R_UpperArm";
  pixelcloth::core::writeTextAtomically(dir / "map.json", map.dump());
  const pm::Motion motion = pm::retarget(renamedClip, skeleton, pm::readJointMap(dir / "map.json", renamedClip));
  for (int k = 0; k < 10; ++k)
    EXPECT_LT(rotationDistance(motion.poses[2].rotations[k], made.poses[2].rotations[k]), 1e-4);
  map["l_forearm"] = "LeftElbow";
  pixelcloth::core::writeTextAtomically(dir / "map.json", map.dump());
  EXPECT_NE(inputErrorOf([&] { pm::readJointMap(dir / "map.json", renamedClip); }).find("no joint 'LeftElbow'"),
            std::string::npos);
  map["l_forearm"] = "LeftForeArm";
  map["l_hand"] = "LeftHand";
  pixelcloth::core::writeTextAtomically(dir / "map.json", map.dump());
  EXPECT_NE(inputErrorOf([&] { pm::readJointMap(dir / "map.json", renamedClip); }).find("unknown joint 'l_hand'"),
            std::string::npos);
}

TEST(Sequence, PointCachesReadBackAndDamagedOnesAreRefused) {
  const fs::path dir = pixelcloth::testing::freshDir("pc2");
  std::vector<Eigen::MatrixX3d> frames;
  for (int f = 0; f < 3; ++f) frames.push_back(Eigen::MatrixX3d::Random(5, 3) + Eigen::MatrixX3d::Constant(5, 3, f));
  pm::writePc2(dir / "a.pc2", frames);
  const std::vector<Eigen::MatrixX3f> back = pm::readPc2(dir / "a.pc2");
  ASSERT_EQ(back.size(), 3u);
  for (int f = 0; f < 3; ++f) EXPECT_LT((back[f].cast<double>() - frames[f]).cwiseAbs().maxCoeff(), 1e-6);
  const std::string bytes = pixelcloth::core::readTextFile(dir / "a.pc2");
  pixelcloth::core::writeTextAtomically(dir / "cut.pc2", bytes.substr(0, bytes.size() - 7));
  EXPECT_NE(inputErrorOf([&] { pm::readPc2(dir / "cut.pc2"); }).find("cut.pc2"), std::string::npos);
  pixelcloth::core::writeTextAtomically(dir / "other.pc2", "POINTCACHE3" + bytes.substr(11));
  EXPECT_NE(inputErrorOf([&] { pm::readPc2(dir / "other.pc2"); }).find("not a PC2 point cache"), std::string::npos);
  frames[1](2, 1) = std::nan("");
  EXPECT_NE(inputErrorOf([&] { pm::writePc2(dir / "nan.pc2", frames); }).find("frame 1"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "nan.pc2"));
}

TEST(Sequence, JitterIsTheSecondDifferenceAndInsideTheBodyIsCounted) {
  // The body: an octahedron of radius 1 at the origin, still. The garment: one point gliding outside at constant
  // speed (no jitter), one shaking inside by +-1 mm along x.
  Eigen::MatrixX3d octahedron(6, 3);
  octahedron << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  Eigen::MatrixX3i faces(8, 3);
  faces << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  std::vector<Eigen::MatrixX3d> garment, body;
  for (int f = 0; f < 5; ++f) {
    Eigen::MatrixX3d g(2, 3);
    g << 2 + 0.01 * f, 0, 0, (f % 2 ? 0.001 : -0.001), 0, 0.5;
    garment.push_back(g);
    body.push_back(octahedron);
  }
  const pm::TemporalMetrics m = pm::temporalMetrics(garment, body, faces, 30);
  ASSERT_EQ(m.insideVertices.size(), 5u);
  EXPECT_TRUE(std::isnan(m.garmentJitterCm.front()) && std::isnan(m.garmentJitterCm.back()));
  // |x(t+1) - 2 x(t) + x(t-1)| = 4 mm for the shaking point, 0 for the gliding one: a mean of 0.2 cm.
  for (int f = 1; f < 4; ++f) EXPECT_NEAR(m.garmentJitterCm[f], 0.2, 1e-9);
  EXPECT_NEAR(m.meanBodyJitterCm(), 0, 1e-12);
  for (int f = 0; f < 5; ++f) {
    EXPECT_EQ(m.insideVertices[f], 1);
    // The inside point (+-0.001, 0, 0.5) is nearest the face x + y + z = 1 (or -x + y + z = 1): (1 - 0.501) / sqrt(3).
    EXPECT_NEAR(m.maxDepthCm[f], 100 * (1 - 0.5 - 0.001) / std::sqrt(3.0), 1e-6);
  }
  EXPECT_EQ(m.framesWithInside(), 5);
  EXPECT_EQ(m.toJson()["inside_body"]["frames_with_any"], 5);
}

TEST(Sequence, TheAnimatedGlbReadsBackThroughAssimp) {
  const pb::Body& body = pixelcloth::testing::coarseMannequin();
  pixelcloth::core::Mesh garment;
  garment.V.resize(4, 3);
  garment.V << 0, 1, 0.2, 0.1, 1, 0.2, 0, 1.1, 0.2, 0.1, 1.1, 0.2;
  garment.F.resize(2, 3);
  garment.F << 0, 1, 2, 1, 3, 2;
  pm::AnimatedScene scene;
  scene.body = &body;
  scene.garment = &garment;
  scene.fps = 24;
  scene.rootTranslations.resize(3, 3);
  for (int f = 0; f < 3; ++f) {
    scene.poses.push_back(pb::randomPose(7 + f, 0.7));
    scene.rootRotations.push_back(axisRotation(1, 20.0 * f));
    scene.rootTranslations.row(f) << 0.1 * f, 0, -0.05 * f;
    scene.garmentFrames.push_back(garment.V + Eigen::MatrixX3d::Constant(4, 3, 0.01 * f));
  }
  const fs::path dir = pixelcloth::testing::freshDir("glb");
  pm::writeAnimatedGlb(dir / "scene.glb", scene);

  Assimp::Importer importer;
  const aiScene* read = importer.ReadFile((dir / "scene.glb").string(), 0);
  ASSERT_TRUE(read) << importer.GetErrorString();
  const aiMesh *cloth = nullptr, *skin = nullptr;
  for (unsigned m = 0; m < read->mNumMeshes; ++m) {
    if (read->mMeshes[m]->mNumVertices == 4) cloth = read->mMeshes[m];
    if (read->mMeshes[m]->mNumBones > 0) skin = read->mMeshes[m];
  }
  ASSERT_TRUE(cloth && skin);
  EXPECT_EQ(static_cast<int>(skin->mNumVertices), body.mesh.numVertices());
  EXPECT_GE(skin->mNumBones, 10u);
  ASSERT_EQ(cloth->mNumAnimMeshes, 2u);  // frames 1 and 2
  // assimp gives a target's positions as the shape itself (base plus displacement): frame 2's.
  const aiVector3D corner = cloth->mAnimMeshes[1]->mVertices[3];
  EXPECT_LT((Eigen::Vector3d(corner.x, corner.y, corner.z) - scene.garmentFrames[2].row(3).transpose()).norm(), 1e-6);
  ASSERT_EQ(read->mNumAnimations, 1u);
  const aiAnimation& animation = *read->mAnimations[0];
  const aiNodeAnim *arm = nullptr, *root = nullptr;
  for (unsigned c = 0; c < animation.mNumChannels; ++c) {
    const std::string name = animation.mChannels[c]->mNodeName.C_Str();
    if (name == "l_arm") arm = animation.mChannels[c];
    if (name == "root") root = animation.mChannels[c];
  }
  ASSERT_TRUE(arm && root);
  ASSERT_EQ(arm->mNumRotationKeys, 3u);
  for (int f = 0; f < 3; ++f) {
    const aiQuaternion q = arm->mRotationKeys[f].mValue;
    const Eigen::Matrix3d r = Eigen::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix();
    EXPECT_LT(rotationDistance(r, scene.poses[f].rotations[5]), 1e-5);
  }
  ASSERT_EQ(root->mNumPositionKeys, 3u);
  const Eigen::Vector3d rest = body.skeleton.positions.row(body.skeleton.index("root")).transpose();
  const aiVector3D moved = root->mPositionKeys[2].mValue;
  EXPECT_LT((Eigen::Vector3d(moved.x, moved.y, moved.z) - rest - Eigen::Vector3d(0.2, 0, -0.1)).norm(), 1e-6);
  EXPECT_NEAR(root->mPositionKeys[2].mTime / (animation.mTicksPerSecond > 0 ? animation.mTicksPerSecond : 1), 2 / 24.0,
              1e-4);

  // And as a clip: our own joint names are a built-in map, and the poses and root motion come back.
  const pm::Clip clip = pm::readClip(dir / "scene.glb");
  EXPECT_NEAR(clip.fps, 24, 1e-3);
  const pm::JointMap map = pm::detectJointMap(clip);
  EXPECT_EQ(map.name, "pixelcloth");
  const pm::Motion motion = pm::retarget(clip, body.skeleton, map);
  ASSERT_EQ(motion.frames(), 3);
  for (int f = 0; f < 3; ++f) {
    for (int k = 0; k < 10; ++k)
      EXPECT_LT(rotationDistance(motion.poses[f].rotations[k], scene.poses[f].rotations[k]), 1e-4) << f << " " << k;
    EXPECT_LT(rotationDistance(motion.rootRotations[f], scene.rootRotations[f]), 1e-5);
    EXPECT_LT((motion.rootTranslations.row(f) - scene.rootTranslations.row(f)).norm(), 1e-5);
  }
}

// glTF clips are checked before assimp, whose glTF readers read past the end of a damaged file (docs/reliability.md,
// finding 17): the GLB of the test above, truncated or with another length in its header, and text that is not a
// glTF file's JSON, are refused naming the file.
TEST(Sequence, DamagedGltfAndGlbClipsAreRefusedBeforeAssimpReadsThem) {
  const fs::path dir = pixelcloth::testing::freshDir("bad_gltf");
  const pb::Body& body = pixelcloth::testing::coarseMannequin();
  pm::AnimatedScene scene;
  scene.body = &body;
  scene.fps = 24;
  scene.rootTranslations = Eigen::MatrixX3d::Zero(2, 3);
  for (int f = 0; f < 2; ++f) {
    scene.poses.push_back(pb::randomPose(3 + f, 0.5));
    scene.rootRotations.push_back(axisRotation(1, 10.0 * f));
  }
  pm::writeAnimatedGlb(dir / "scene.glb", scene);
  EXPECT_NO_THROW(pm::readClip(dir / "scene.glb"));
  const std::string glb = pixelcloth::core::readTextFile(dir / "scene.glb");
  const auto errorOf = [&](const std::string& name, const std::string& bytes) {
    pixelcloth::core::writeTextAtomically(dir / name, bytes);
    return inputErrorOf([&] { pm::readClip(dir / name); });
  };
  const std::string cut = errorOf("cut.glb", glb.substr(0, glb.size() / 2));
  EXPECT_NE(cut.find("cut.glb: the binary glTF header says"), std::string::npos) << cut;
  std::string longer = glb;
  longer[8] = static_cast<char>(longer[8] + 4);  // the header's total length
  EXPECT_NE(errorOf("longer.glb", longer).find("truncated or damaged"), std::string::npos);
  std::string json = glb;
  json[12] = static_cast<char>(0xff);  // the JSON chunk's length, far past the end
  json[13] = static_cast<char>(0xff);
  json[14] = static_cast<char>(0xff);
  EXPECT_NE(errorOf("chunk.glb", json).find("runs past the end"), std::string::npos);
  EXPECT_NE(errorOf("words.gltf", "{\"scenes\": []}").find("not a glTF file"), std::string::npos);
  // What the clip fuzz target found: 17 bytes that made assimp's glTF reader run past its buffer.
  const std::string found =
      inputErrorOf([&] { pm::readClip(pixelcloth::testing::asset("fuzz_clip_gltf_overflow.gltf")); });
  EXPECT_NE(found.find("fuzz_clip_gltf_overflow.gltf"), std::string::npos) << found;
}

TEST(Sequence, PlainMeshesGlbKeepsFramesColoursAndNamesForAssimp) {
  // Two meshes: a square of two triangles over three frames with vertex colours and an application colour set, and
  // a still triangle.
  pm::GlbMesh square{"garment_0", Eigen::MatrixX3i(2, 3), {}, {}};
  square.faces << 0, 1, 2, 1, 3, 2;
  Eigen::MatrixX3d V(4, 3);
  V << 0, 1, 0.2, 0.1, 1, 0.2, 0, 1.1, 0.2, 0.1, 1.1, 0.2;
  for (int f = 0; f < 3; ++f) square.frames.push_back(V + Eigen::MatrixX3d::Constant(4, 3, 0.01 * f));
  square.colors["COLOR_0"] = Eigen::MatrixX3f::Constant(4, 3, 0.5f);
  square.colors["_PATCH"] = Eigen::MatrixX3f::Identity(4, 3);
  pm::GlbMesh still{"body", Eigen::MatrixX3i(1, 3), {V.topRows(3)}, {}};
  still.faces << 0, 1, 2;
  const fs::path dir = pixelcloth::testing::freshDir("meshes_glb");
  const std::string bytes = pm::meshesGlb({square, still}, 24);
  ASSERT_EQ(bytes.substr(0, 4), "glTF");
  {
    std::ofstream out(dir / "scene.glb", std::ios::binary);
    out << bytes;
  }
  Assimp::Importer importer;
  const aiScene* read = importer.ReadFile((dir / "scene.glb").string(), 0);
  ASSERT_TRUE(read) << importer.GetErrorString();
  ASSERT_EQ(read->mNumMeshes, 2u);
  const aiMesh *cloth = nullptr, *body = nullptr;
  for (unsigned m = 0; m < read->mNumMeshes; ++m)
    (read->mMeshes[m]->mNumVertices == 4 ? cloth : body) = read->mMeshes[m];
  ASSERT_TRUE(cloth && body);
  EXPECT_EQ(std::string(cloth->mName.C_Str()), "garment_0");
  EXPECT_EQ(cloth->mNumFaces, 2u);  // 16-bit indices read back
  EXPECT_EQ(cloth->mFaces[1].mIndices[1], 3u);
  ASSERT_TRUE(cloth->HasVertexColors(0));
  EXPECT_NEAR(cloth->mColors[0][2].g, 0.5, 1e-6);
  ASSERT_EQ(cloth->mNumAnimMeshes, 2u);
  const aiVector3D corner = cloth->mAnimMeshes[1]->mVertices[3];
  EXPECT_LT((Eigen::Vector3d(corner.x, corner.y, corner.z) - square.frames[2].row(3).transpose()).norm(), 1e-6);
  EXPECT_EQ(body->mNumAnimMeshes, 0u);

  // Refused: frames of another size, positions that are not finite, colours of another size, faces beyond the mesh.
  pm::GlbMesh bad = square;
  bad.frames[1] = V.topRows(3);
  EXPECT_THROW(pm::meshesGlb({bad}), pixelcloth::core::InputError);
  bad = square;
  bad.frames[2](0, 0) = std::nan("");
  EXPECT_THROW(pm::meshesGlb({bad}), pixelcloth::core::InputError);
  bad = square;
  bad.colors["_ERROR"] = Eigen::MatrixX3f::Zero(3, 3);
  EXPECT_THROW(pm::meshesGlb({bad}), pixelcloth::core::InputError);
  bad = square;
  bad.faces(0, 0) = 4;
  EXPECT_THROW(pm::meshesGlb({bad}), pixelcloth::core::InputError);
}

TEST(Sequence, ABodyAloneIsAnAnimatedGlbToo) {
  const pb::Body& body = pixelcloth::testing::coarseMannequin();
  pm::AnimatedScene scene;
  scene.body = &body;
  scene.fps = 24;
  const int frames = 73;
  scene.rootTranslations = Eigen::MatrixX3d::Zero(frames, 3);
  for (int f = 0; f < frames; ++f) {
    scene.poses.push_back(pb::randomPose(f, 0.5));
    scene.rootRotations.push_back(Eigen::Matrix3d::Identity());
  }
  const fs::path dir = pixelcloth::testing::freshDir("glb_body");
  pm::writeAnimatedGlb(dir / "body.glb", scene);
  const pm::Clip clip = pm::readClip(dir / "body.glb");
  EXPECT_EQ(clip.frames(), frames);
}

// Marker trajectories as capture systems export them: NPY in either layout and precision, CSV with a header, blanks
// and nan for lost markers; the damaged ones refused naming the file and where.
TEST(Trajectories, NpyAndCsvReadBackWithLostMarkersAndBadOnesAreRefused) {
  const fs::path dir = pixelcloth::testing::freshDir("trajectories");
  const double nan = std::nan("");
  pm::MarkerTrajectories written;
  for (int f = 0; f < 3; ++f) written.frames.push_back(Eigen::MatrixX3d::Random(4, 3));
  written.frames[1].row(2).setConstant(nan);  // lost in frame 2
  pm::writeMarkerTrajectories(dir / "t.npy", written);
  auto same = [&](const pm::MarkerTrajectories& read) {
    ASSERT_EQ(read.numFrames(), 3);
    ASSERT_EQ(read.markers(), 4);
    for (int f = 0; f < 3; ++f)
      for (int m = 0; m < 4; ++m)
        if (f == 1 && m == 2)
          EXPECT_TRUE(read.frames[f].row(m).array().isNaN().all());
        else
          EXPECT_LT((read.frames[f].row(m) - written.frames[f].row(m)).norm(), 1e-6) << f << " " << m;
  };
  same(pm::readMarkerTrajectories(dir / "t.npy", 4, "m.json"));

  // (frames, 3M) float64, as numpy.savetxt users reshape theirs.
  std::vector<double> flat;
  for (const Eigen::MatrixX3d& frame : written.frames)
    for (int m = 0; m < 4; ++m)
      for (int c = 0; c < 3; ++c) flat.push_back(frame(m, c));
  pixelcloth::core::writeNpy(dir / "flat.npy", flat, {3, 12});
  same(pm::readMarkerTrajectories(dir / "flat.npy", 4, "m.json"));

  // CSV: a header, a comment, the lost marker as blanks in one frame.
  std::ostringstream csv;
  csv << "# exported\n";
  for (int m = 0; m < 4; ++m) csv << (m ? "," : "") << "m" << m << "_x,m" << m << "_y,m" << m << "_z";
  csv << "\n" << std::setprecision(17);
  for (int f = 0; f < 3; ++f) {
    for (int m = 0; m < 4; ++m)
      for (int c = 0; c < 3; ++c) {
        csv << (m || c ? "," : "");
        if (f != 1 || m != 2)
          csv << written.frames[f](m, c);
        else if (c == 0)
          csv << "NaN";
      }
    csv << "\n";
  }
  pixelcloth::core::writeTextAtomically(dir / "t.csv", csv.str());
  same(pm::readMarkerTrajectories(dir / "t.csv", 4, "m.json"));

  auto refusal = [&](const std::string& name, int markers = 4) {
    return inputErrorOf([&] { pm::readMarkerTrajectories(dir / name, markers, "m.json"); });
  };
  EXPECT_NE(refusal("t.npy", 5).find("expected (frames, 5, 3)"), std::string::npos) << refusal("t.npy", 5);
  EXPECT_NE(refusal("t.csv", 5).find("line 3: 12 columns, expected 15"), std::string::npos) << refusal("t.csv", 5);
  EXPECT_NE(refusal("missing.npy").find("missing.npy"), std::string::npos);
  pixelcloth::core::writeTextAtomically(dir / "t.txt", "1,2,3\n");
  EXPECT_NE(refusal("t.txt").find("expected marker trajectories as .npy"), std::string::npos);
  pm::MarkerTrajectories partial = written;
  partial.frames[2](3, 1) = nan;
  pm::writeMarkerTrajectories(dir / "partial.npy", partial);
  EXPECT_NE(refusal("partial.npy").find("frame 3, marker 4 has 1 of its 3 coordinates NaN"), std::string::npos)
      << refusal("partial.npy");
  partial.frames[2](3, 1) = std::numeric_limits<double>::infinity();
  pm::writeMarkerTrajectories(dir / "inf.npy", partial);
  EXPECT_NE(refusal("inf.npy").find("frame 3, marker 4 is infinite"), std::string::npos) << refusal("inf.npy");
  pixelcloth::core::writeTextAtomically(dir / "empty.csv", "x,y,z\n");
  EXPECT_NE(refusal("empty.csv", 1).find("no frames"), std::string::npos);
  pixelcloth::core::writeTextAtomically(dir / "word.csv", "1,2,3\n1,two,3\n");
  EXPECT_NE(refusal("word.csv", 1).find("line 2: expected 3 comma-separated numbers"), std::string::npos);
  std::string bytes = pixelcloth::core::readTextFile(dir / "t.npy");
  pixelcloth::core::writeTextAtomically(dir / "cut.npy", bytes.substr(0, bytes.size() - 5));
  EXPECT_NE(refusal("cut.npy").find("cut.npy"), std::string::npos);
}

// Positions in the clip's world (a capture's markers) brought into the fixed-root frame are where the root motion
// took them from; a lost marker stays lost.
TEST(Motion, RootMotionUndoneIsTheInverseOfRootMotion) {
  pm::Motion motion;
  motion.fps = 30;
  for (int f = 0; f < 3; ++f) {
    motion.poses.emplace_back();
    motion.rootRotations.push_back(axisRotation(1, 20.0 * f) * axisRotation(0, 5.0 * f));
  }
  motion.rootTranslations = Eigen::MatrixX3d::Random(3, 3);
  const Eigen::Vector3d root(0.1, 1.0, -0.05);
  std::vector<Eigen::MatrixX3d> frames;
  for (int f = 0; f < 3; ++f) frames.push_back(Eigen::MatrixX3d::Random(6, 3));
  const std::vector<Eigen::MatrixX3d> world = pm::withRootMotion(frames, motion, root);
  EXPECT_GT((world[2] - frames[2]).norm(), 0.1);
  const std::vector<Eigen::MatrixX3d> back = pm::withoutRootMotion(world, motion, root);
  for (int f = 0; f < 3; ++f) EXPECT_LT((back[f] - frames[f]).cwiseAbs().maxCoeff(), 1e-12) << f;
  std::vector<Eigen::MatrixX3d> lost = world;
  lost[1].row(4).setConstant(std::nan(""));
  const std::vector<Eigen::MatrixX3d> lostBack = pm::withoutRootMotion(lost, motion, root);
  EXPECT_TRUE(lostBack[1].row(4).array().isNaN().all());
  EXPECT_LT((lostBack[1].row(3) - frames[1].row(3)).norm(), 1e-12);
}
