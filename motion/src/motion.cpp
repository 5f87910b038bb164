#include "pixelcloth/motion/motion.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/npy.h"

namespace pixelcloth::motion {

namespace fs = std::filesystem;

namespace {

/// Where each of our mapped joints' bones ends: the mapped joint that continues it, or "" for a leaf (the neck ends
/// at the head, a forearm at the wrist), whose end JointMap::ends or the clip's first child gives.
const std::map<std::string, std::string>& boneContinuation() {
  static const std::map<std::string, std::string> next = {
      {"lower_back", "spine"}, {"spine", "spine1"},    {"spine1", "neck"}, {"neck", ""},
      {"l_shoulder", "l_arm"}, {"l_arm", "l_forearm"}, {"l_forearm", ""},  {"r_shoulder", "r_arm"},
      {"r_arm", "r_forearm"},  {"r_forearm", ""}};
  return next;
}

/// A joint name as compared: after the last ':', without the "m_avg_"/"f_avg_" prefixes of SMPL's files, lower
/// case, without '_', ' ', '-' and '.'.
std::string normalised(const std::string& name) {
  std::string s = name.substr(name.find_last_of(':') == std::string::npos ? 0 : name.find_last_of(':') + 1);
  std::string out;
  for (char c : s)
    if (c != '_' && c != ' ' && c != '-' && c != '.')
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* prefix : {"mavg", "favg"})
    if (out.rfind(prefix, 0) == 0 && out.size() > 4) out = out.substr(4);
  return out;
}

/// The clip joint whose name matches one of `candidates` ('|'-separated), or -1: a name spelled exactly first (an
/// importer's own top node may be called "ROOT"), then one matching as normalised() compares.
int findJoint(const Clip& clip, const std::string& candidates) {
  {
    std::istringstream in(candidates);
    for (std::string candidate; std::getline(in, candidate, '|');)
      if (clip.find(candidate) >= 0) return clip.find(candidate);
  }
  std::istringstream in(candidates);
  for (std::string candidate; std::getline(in, candidate, '|');) {
    const std::string wanted = normalised(candidate);
    for (int j = 0; j < static_cast<int>(clip.joints.size()); ++j)
      if (normalised(clip.joints[j]) == wanted) return j;
  }
  return -1;
}

std::string listJoints(const Clip& clip) {
  std::ostringstream out;
  for (size_t j = 0; j < clip.joints.size(); ++j) out << (j ? ", " : "") << clip.joints[j];
  return out.str();
}

JointMap makeMap(const std::string& name, const std::vector<std::string>& joints,
                 const std::map<std::string, std::string>& ends) {
  JointMap map{name, {}, ends};
  for (size_t k = 0; k < joints.size(); ++k) map.joints[mappedJoints()[k]] = joints[k];
  return map;
}

/// The clip joint a bone of `ours`, driven by clip joint `c`, ends at; -1 when there is none.
int boneEnd(const Clip& clip, const JointMap& map, const std::string& ours, int c) {
  const std::string& next = boneContinuation().at(ours);
  if (!next.empty()) return clip.find(map.joints.at(next));
  const auto end = map.ends.find(ours);
  if (end != map.ends.end()) {
    const int e = clip.find(end->second);
    if (e >= 0) return e;
  }
  const std::vector<int> children = clip.children(c);
  return children.empty() ? -1 : children.front();
}

/// Upper arms of a clip's rest pose within this angle of ours count as resting alike (a T-pose either way).
constexpr double kArmRestToleranceDegrees = 10.0;

/// How far beyond a joint limit a retargeted angle may land and still count as within (see retarget()).
constexpr double kRetargetSlackDegrees = 1.0;

/// `rotation`, or the axis permutation (a rotation taking each axis onto an axis) within 10 degrees of it.
Eigen::Matrix3d snappedToAxes(const Eigen::Matrix3d& rotation) {
  Eigen::Matrix3d best = rotation;
  double bestTrace = -4;
  const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& order : orders)
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
      for (int r = 0; r < 3; ++r) P(r, order[r]) = (signs >> r) & 1 ? -1 : 1;
      if (P.determinant() < 0) continue;
      const double trace = (P.transpose() * rotation).trace();
      if (trace > bestTrace) {
        bestTrace = trace;
        best = P;
      }
    }
  const double degrees = std::acos(std::clamp((bestTrace - 1) / 2, -1.0, 1.0)) * 180 / M_PI;
  return degrees < 10 ? best : rotation;
}

Eigen::Matrix3d orthonormalised(const Eigen::Matrix3d& r) {
  return Eigen::Quaterniond(r).normalized().toRotationMatrix();
}

}  // namespace

const std::vector<std::string>& mappedJoints() {
  static const std::vector<std::string> joints = {"root",       "lower_back", "spine",    "spine1",
                                                  "neck",       "l_shoulder", "l_arm",    "l_forearm",
                                                  "r_shoulder", "r_arm",      "r_forearm"};
  return joints;
}

nlohmann::json JointMap::toJson() const { return {{"name", name}, {"joints", joints}, {"ends", ends}}; }

const std::vector<JointMap>& builtinJointMaps() {
  static const std::vector<JointMap> maps = {
      makeMap("cmu",
              {"Hips", "LowerBack", "Spine", "Spine1", "Neck", "LeftShoulder", "LeftArm", "LeftForeArm",
               "RightShoulder", "RightArm", "RightForeArm"},
              {{"neck", "Head"}, {"l_forearm", "LeftHand"}, {"r_forearm", "RightHand"}}),
      makeMap("mixamo",
              {"Hips", "Spine", "Spine1", "Spine2", "Neck", "LeftShoulder", "LeftArm", "LeftForeArm", "RightShoulder",
               "RightArm", "RightForeArm"},
              {{"neck", "Head"}, {"l_forearm", "LeftHand"}, {"r_forearm", "RightHand"}}),
      makeMap("smpl",
              {"pelvis", "spine1", "spine2", "spine3", "neck", "left_collar|L_Collar", "left_shoulder|L_Shoulder",
               "left_elbow|L_Elbow", "right_collar|R_Collar", "right_shoulder|R_Shoulder", "right_elbow|R_Elbow"},
              {{"neck", "head"}, {"l_forearm", "left_wrist|L_Wrist"}, {"r_forearm", "right_wrist|R_Wrist"}}),
      // pixelcloth's own joint names, as its animated GLBs carry them.
      makeMap("pixelcloth", mappedJoints(), {{"neck", "head"}}),
  };
  return maps;
}

JointMap detectJointMap(const Clip& clip) {
  std::ostringstream missing;
  for (const JointMap& map : builtinJointMaps()) {
    JointMap resolved{map.name, {}, {}};
    std::vector<std::string> lacking;
    for (const auto& [ours, candidates] : map.joints) {
      const int c = findJoint(clip, candidates);
      if (c < 0)
        lacking.push_back(candidates);
      else
        resolved.joints[ours] = clip.joints[c];
    }
    for (const auto& [ours, candidates] : map.ends) {
      const int c = findJoint(clip, candidates);
      if (c >= 0) resolved.ends[ours] = clip.joints[c];
    }
    if (lacking.empty()) return resolved;
    missing << "\n  " << map.name << ": lacks";
    for (const std::string& name : lacking) missing << " " << name;
  }
  PIXELCLOTH_FAIL(clip.source << ": its joints match none of the built-in joint maps:" << missing.str()
                              << "\nthe clip's joints: " << listJoints(clip)
                              << "\nname the clip joint of each of ours in a --map file: {\"root\": \"...\", "
                                 "\"lower_back\": \"...\", ..., \"r_forearm\": \"...\"}");
}

JointMap readJointMap(const fs::path& path, const Clip& clip) {
  const nlohmann::json json = core::readJson(path);
  const std::string context = path.string();
  PIXELCLOTH_CHECK(json.is_object(), context << ": expected an object mapping our joints to the clip's");
  JointMap map{context, {}, {}};
  const std::set<std::string> ours(mappedJoints().begin(), mappedJoints().end());
  auto resolve = [&](const std::string& key, const nlohmann::json& value) {
    PIXELCLOTH_CHECK(value.is_string(), context << ": \"" << key << "\" must name a joint of the clip");
    const std::string name = value.get<std::string>();
    PIXELCLOTH_CHECK(clip.find(name) >= 0, context << ": \"" << key << "\": the clip " << clip.source
                                                   << " has no joint '" << name
                                                   << "'; its joints: " << listJoints(clip));
    return name;
  };
  for (const auto& [key, value] : json.items()) {
    if (key == "ends") {
      PIXELCLOTH_CHECK(value.is_object(), context << ": \"ends\" must be an object");
      for (const auto& [end, name] : value.items()) {
        PIXELCLOTH_CHECK(ours.count(end), context << ": \"ends\": unknown joint '" << end << "'");
        map.ends[end] = resolve("ends." + end, name);
      }
      continue;
    }
    PIXELCLOTH_CHECK(ours.count(key), context << ": unknown joint '" << key
                                              << "'; expected root, lower_back, spine, "
                                                 "spine1, neck, l_shoulder, l_arm, l_forearm, r_shoulder, r_arm, "
                                                 "r_forearm and, optionally, ends");
    map.joints[key] = resolve(key, value);
  }
  for (const std::string& joint : mappedJoints())
    PIXELCLOTH_CHECK(map.joints.count(joint), context << ": names no clip joint for our '" << joint << "'");
  return map;
}

Motion retarget(const Clip& clip, const body::Skeleton& skeleton, const JointMap& map,
                body::BeyondLimits beyondLimits) {
  PIXELCLOTH_CHECK(clip.frames() > 0, clip.source << ": the clip has no frames");
  std::map<std::string, int> c;  // our mapped joint -> clip joint
  for (const std::string& ours : mappedJoints()) {
    const auto it = map.joints.find(ours);
    PIXELCLOTH_CHECK(it != map.joints.end(), "joint map " << map.name << ": names no clip joint for '" << ours << "'");
    c[ours] = clip.find(it->second);
    PIXELCLOTH_CHECK(c[ours] >= 0, "joint map " << map.name << ": the clip " << clip.source << " has no joint '"
                                                << it->second << "'");
  }
  // The clip's axes in ours: its rest pose's frame (up from the root to the neck, left from the right arm to the left,
  // and their cross product) onto the same frame of our rest pose.
  auto restFrame = [](const Eigen::RowVector3d& root, const Eigen::RowVector3d& neck, const Eigen::RowVector3d& leftArm,
                      const Eigen::RowVector3d& rightArm, const std::string& context) {
    Eigen::Vector3d up = (neck - root).transpose(), left = (leftArm - rightArm).transpose();
    PIXELCLOTH_CHECK(up.norm() > 0 && left.norm() > 0,
                     context << ": the rest pose puts the root on the neck or one arm on the other");
    const double length = up.norm();
    up.normalize();
    left -= left.dot(up) * up;
    PIXELCLOTH_CHECK(left.norm() > 1e-6 * length, context << ": the rest pose's arms lie along its spine");
    left.normalize();
    Eigen::Matrix3d frame;
    frame << left, up, left.cross(up);
    return std::pair<Eigen::Matrix3d, double>{frame, length};
  };
  const Eigen::RowVector3d restRoot = clip.restPositions.row(c["root"]);
  const auto [clipFrame, clipSpine] =
      restFrame(restRoot, clip.restPositions.row(c["neck"]), clip.restPositions.row(c["l_arm"]),
                clip.restPositions.row(c["r_arm"]), clip.source);
  const int ourRoot = skeleton.index("root");
  const auto [ourFrame, ourSpine] = restFrame(
      skeleton.positions.row(ourRoot), skeleton.positions.row(skeleton.index("neck")),
      skeleton.positions.row(skeleton.index("l_arm")), skeleton.positions.row(skeleton.index("r_arm")), "skeleton");
  // Clips are authored in axes that are ours up to a quarter turn (Y or Z up, facing along an axis); a few degrees off
  // such a turn is the two skeletons' differing spines and shoulders, which would tilt every joint's axis.
  const Eigen::Matrix3d A = snappedToAxes(ourFrame * clipFrame.transpose());

  // The rest poses' one difference that is motion rather than anatomy: where the upper arms point (a T-pose, an
  // A-pose, or between), when they differ by more than kArmRestToleranceDegrees. Each upper arm gets the rotation
  // taking our rest bone onto the clip's, and the forearm inherits it. Every other joint is taken to rest as ours does,
  // whatever its bones' directions: a clip's clavicles may rise 20 degrees at rest and its spine bend, which is its
  // skeleton, not a pose.
  const std::array<int, 10> ourJoints = skeleton.poseJointIndices();
  std::vector<Eigen::Matrix3d> correction(skeleton.numJoints(), Eigen::Matrix3d::Identity());
  for (int k = 0; k < 10; ++k) {
    const std::string& ours = body::kPoseJoints[k];
    const int j = ourJoints[k];
    const int parent = skeleton.parents[j];
    correction[j] = parent < 0 ? Eigen::Matrix3d::Identity() : correction[parent];
    if (ours != "l_arm" && ours != "r_arm") continue;
    const std::string& next = boneContinuation().at(ours);
    const Eigen::Vector3d bone = (skeleton.positions.row(skeleton.index(next)) - skeleton.positions.row(j)).transpose();
    const int end = boneEnd(clip, map, ours, c[ours]);
    if (end < 0) continue;
    const Eigen::Vector3d clipBone = A * (clip.restPositions.row(end) - clip.restPositions.row(c[ours])).transpose();
    // A few degrees between the arms is anatomy as well (and turning the arm by them would tilt every elbow bend).
    if (bone.norm() > 0 && clipBone.norm() > 0 &&
        bone.normalized().dot(clipBone.normalized()) < std::cos(kArmRestToleranceDegrees * M_PI / 180))
      correction[j] = Eigen::Quaterniond::FromTwoVectors(bone, clipBone).toRotationMatrix();
  }

  Motion motion;
  motion.fps = clip.fps;
  motion.map = map;
  motion.source = clip.source;
  motion.rootScale = ourSpine / clipSpine;
  motion.rootTranslations.resize(clip.frames(), 3);
  const Eigen::Matrix3d restRootRotation = clip.restRotations[c["root"]];
  for (int f = 0; f < clip.frames(); ++f) {
    const Eigen::Matrix3d rootDelta = clip.rotations[f][c["root"]] * restRootRotation.transpose();
    std::vector<Eigen::Matrix3d> global(skeleton.numJoints(), Eigen::Matrix3d::Identity());
    body::Pose pose;
    for (int k = 0; k < 10; ++k) {
      const int clipJoint = c[body::kPoseJoints[k]];
      // The joint's world rotation from its rest, relative to the root's, in our axes.
      const Eigen::Matrix3d delta =
          rootDelta.transpose() * clip.rotations[f][clipJoint] * clip.restRotations[clipJoint].transpose();
      const int j = ourJoints[k];
      global[j] = A * delta * A.transpose() * correction[j];
      const int parent = skeleton.parents[j];
      pose.rotations[k] =
          orthonormalised((parent < 0 ? Eigen::Matrix3d::Identity() : global[parent]).transpose() * global[j]);
    }
    // Two skeletons' bones never point quite alike, so a retargeted joint that should rest at a limit lands a little
    // beyond it: within kRetargetSlackDegrees it is clamped without counting.
    const std::string beyond = pose.limitViolation(kRetargetSlackDegrees);
    if (!beyond.empty()) {
      PIXELCLOTH_CHECK(beyondLimits == body::BeyondLimits::Clamp,
                       clip.source << ": frame " << f << " (" << f / clip.fps << " s): " << beyond
                                   << "; --clamp-to-limits clamps every frame into the limits");
      ++motion.clampedFrames;
    }
    pose = pose.clampedToLimits();
    motion.poses.push_back(pose);
    motion.rootRotations.push_back(orthonormalised(A * rootDelta * A.transpose()));
    motion.rootTranslations.row(f) =
        motion.rootScale * (A * (clip.positions[f].row(c["root"]) - restRoot).transpose()).transpose();
  }
  if (motion.clampedFrames > 0)
    PIXELCLOTH_WARN(clip.source << ": " << motion.clampedFrames << " of " << clip.frames()
                                << " frames clamped into the joint limits");
  return motion;
}

namespace {
/// Each frame turned about `rootPosition` by the clip's root rotation and shifted by its displacement, or (inverse)
/// the way back.
std::vector<Eigen::MatrixX3d> movedByRoot(const std::vector<Eigen::MatrixX3d>& frames, const Motion& motion,
                                          const Eigen::Vector3d& rootPosition, bool inverse) {
  PIXELCLOTH_CHECK(static_cast<int>(frames.size()) == motion.frames(),
                   "root motion: " << frames.size() << " frames for a motion of " << motion.frames());
  std::vector<Eigen::MatrixX3d> out(frames.size());
  for (size_t f = 0; f < frames.size(); ++f) {
    const Eigen::RowVector3d rest = rootPosition.transpose(), moved = rest + motion.rootTranslations.row(f);
    const Eigen::Matrix3d& R = motion.rootRotations[f];
    out[f] = inverse ? Eigen::MatrixX3d(((frames[f].rowwise() - moved) * R).rowwise() + rest)
                     : Eigen::MatrixX3d(((frames[f].rowwise() - rest) * R.transpose()).rowwise() + moved);
  }
  return out;
}
}  // namespace

std::vector<Eigen::MatrixX3d> withRootMotion(const std::vector<Eigen::MatrixX3d>& frames, const Motion& motion,
                                             const Eigen::Vector3d& rootPosition) {
  return movedByRoot(frames, motion, rootPosition, false);
}

std::vector<Eigen::MatrixX3d> withoutRootMotion(const std::vector<Eigen::MatrixX3d>& frames, const Motion& motion,
                                                const Eigen::Vector3d& rootPosition) {
  return movedByRoot(frames, motion, rootPosition, true);
}

void writeMotion(const fs::path& folder, const Motion& motion) {
  PIXELCLOTH_CHECK(motion.frames() > 0, folder.string() << ": a motion of no frames");
  std::vector<float> poses;
  poses.reserve(static_cast<size_t>(motion.frames()) * body::kPoseSize);
  nlohmann::json rotations = nlohmann::json::array(), translations = nlohmann::json::array();
  for (int f = 0; f < motion.frames(); ++f) {
    const Eigen::VectorXf v = motion.poses[f].toVector();
    poses.insert(poses.end(), v.data(), v.data() + v.size());
    std::vector<double> r(9);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) r[3 * a + b] = motion.rootRotations[f](a, b);
    rotations.push_back(r);
    translations.push_back(
        {motion.rootTranslations(f, 0), motion.rootTranslations(f, 1), motion.rootTranslations(f, 2)});
  }
  core::writeNpy(folder / "poses.npy", poses, {motion.frames(), body::kPoseSize});
  const nlohmann::json json = {
      {"format", "pixelcloth-motion"},
      {"version", 1},
      {"fps", motion.fps},
      {"frames", motion.frames()},
      {"source", motion.source},
      {"joint_map", motion.map.toJson()},
      {"clamped_frames", motion.clampedFrames},
      {"poses", "poses.npy"},
      {"root", {{"scale_m_per_unit", motion.rootScale}, {"rotation", rotations}, {"translation_m", translations}}}};
  core::writeJson(folder / "motion.json", json);
}

Motion readMotion(const fs::path& folder, body::BeyondLimits beyondLimits) {
  const fs::path jsonPath = folder / "motion.json";
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_regular_file(jsonPath, ec),
                   folder.string() << ": no motion.json; expected a folder written by `pixelcloth motion import`");
  const nlohmann::json json = core::readJson(jsonPath);
  const std::string context = jsonPath.string();
  PIXELCLOTH_CHECK(json.is_object() && json.value("format", "") == "pixelcloth-motion",
                   context << ": not a pixelcloth motion (expected \"format\": \"pixelcloth-motion\")");
  Motion motion;
  motion.fps = core::requireValue<double>(json, "fps", context);
  PIXELCLOTH_CHECK(std::isfinite(motion.fps) && motion.fps >= 1 && motion.fps <= 1000,
                   context << ": fps " << motion.fps << ", expected 1 to 1000");
  const int frames = core::requireValue<int>(json, "frames", context);
  PIXELCLOTH_CHECK(frames >= 1, context << ": " << frames << " frames, expected 1 or more");
  motion.source = core::valueOr<std::string>(json, "source", "", context);
  motion.clampedFrames = core::valueOr<int>(json, "clamped_frames", 0, context);
  if (json.contains("joint_map") && json["joint_map"].is_object()) {
    const nlohmann::json& m = json["joint_map"];
    motion.map.name = core::valueOr<std::string>(m, "name", "", context + ": joint_map");
    auto names = [&](const char* key, std::map<std::string, std::string>& out) {
      if (!m.contains(key) || !m[key].is_object()) return;
      for (const auto& [ours, theirs] : m[key].items())
        if (theirs.is_string()) out[ours] = theirs.get<std::string>();
    };
    names("joints", motion.map.joints);
    names("ends", motion.map.ends);
  }
  const Eigen::MatrixXf poses = core::readNpyMatrixF(folder / "poses.npy", frames, body::kPoseSize);
  for (int f = 0; f < frames; ++f) {
    const std::string frame = (folder / "poses.npy").string() + ": frame " + std::to_string(f);
    body::Pose pose = body::Pose::fromVector(poses.row(f).transpose(), frame);
    const std::string beyond = pose.limitViolation();
    if (!beyond.empty()) {
      PIXELCLOTH_CHECK(beyondLimits == body::BeyondLimits::Clamp,
                       frame << ": " << beyond << "; --clamp-to-limits clamps every frame into the limits");
      pose = pose.clampedToLimits();
    }
    motion.poses.push_back(pose);
  }
  // The root motion, for export; a motion without one keeps the root still.
  motion.rootRotations.assign(frames, Eigen::Matrix3d::Identity());
  motion.rootTranslations = Eigen::MatrixX3d::Zero(frames, 3);
  if (json.contains("root")) {
    const nlohmann::json& root = json["root"];
    PIXELCLOTH_CHECK(root.is_object(), context << ": \"root\" must be an object");
    motion.rootScale = core::valueOr<double>(root, "scale_m_per_unit", 1.0, context + ": root");
    const nlohmann::json& rotations = core::requireField(root, "rotation", context + ": root");
    const nlohmann::json& translations = core::requireField(root, "translation_m", context + ": root");
    PIXELCLOTH_CHECK(rotations.is_array() && rotations.size() == static_cast<size_t>(frames) &&
                         translations.is_array() && translations.size() == static_cast<size_t>(frames),
                     context << ": root rotation and translation_m must hold one entry per frame (" << frames << ")");
    for (int f = 0; f < frames; ++f) {
      const nlohmann::json& r = rotations[f];
      const nlohmann::json& t = translations[f];
      PIXELCLOTH_CHECK(r.is_array() && r.size() == 9 && t.is_array() && t.size() == 3,
                       context << ": root frame " << f << ": expected 9 rotation and 3 translation numbers");
      for (int a = 0; a < 9; ++a) {
        PIXELCLOTH_CHECK(r[a].is_number() && std::isfinite(r[a].get<double>()),
                         context << ": root frame " << f << ": rotation is not finite numbers");
        motion.rootRotations[f](a / 3, a % 3) = r[a].get<double>();
      }
      for (int a = 0; a < 3; ++a) {
        PIXELCLOTH_CHECK(t[a].is_number() && std::isfinite(t[a].get<double>()),
                         context << ": root frame " << f << ": translation is not finite numbers");
        motion.rootTranslations(f, a) = t[a].get<double>();
      }
      const Eigen::Matrix3d& R = motion.rootRotations[f];
      PIXELCLOTH_CHECK((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-3 && R.determinant() > 0,
                       context << ": root frame " << f << ": rotation is not a rotation");
    }
  }
  return motion;
}

}  // namespace pixelcloth::motion
