#pragma once

// Motion clips retargeted to the body's skeleton (the paper evaluates on CMU motion capture, Sec. 6): a pose of our 10
// joints per frame, relative to a fixed root as the networks take it, and the clip's root motion kept beside for
// export. A motion folder holds motion.json (fps, frames, the joint map, the source, the root motion) and poses.npy
// (frames x 90 float32, DESIGN.md "Pose vector").

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/motion/clip.h"

namespace pixelcloth::motion {

/// Our joints a clip must provide: the root and the 10 posable joints.
const std::vector<std::string>& mappedJoints();

/// Which joint of a clip drives each of ours. `joints` maps each of mappedJoints() to a clip joint; `ends`, optional,
/// names the clip joint where a leaf bone of ours ends (l_forearm: the wrist, neck: the head), which otherwise is the
/// clip joint's first child.
struct JointMap {
  std::string name;  ///< "cmu", "mixamo", "smpl", or the file it was read from
  std::map<std::string, std::string> joints;
  std::map<std::string, std::string> ends;

  nlohmann::json toJson() const;
};

/// The built-in maps: CMU (the BVH conversions of the CMU motion-capture database: Hips, LowerBack, Spine, Spine1,
/// Neck, LeftShoulder, LeftArm, LeftForeArm, ...), Mixamo (Hips, Spine, Spine1, Spine2, Neck, LeftShoulder, ...;
/// "mixamorig:" prefixes ignored), SMPL (pelvis, spine1-3, neck, left_collar, left_shoulder, left_elbow, ...) and
/// pixelcloth's own (root, lower_back, ..., r_forearm: what writeAnimatedGlb names the joints).
/// Names are matched ignoring case, underscores, spaces and any prefix up to a ':'.
const std::vector<JointMap>& builtinJointMaps();

/// The first built-in map every one of whose joints `clip` has, resolved to the clip's own names. Throws InputError
/// listing, for each built-in map, the joints the clip lacks, and pointing at --map.
JointMap detectJointMap(const Clip& clip);

/// A map from a JSON file: {"root": "Hips", "lower_back": "...", ..., "ends": {"l_forearm": "LeftHand"}}. Every one of
/// mappedJoints() must be named; unknown keys are refused. Resolved against `clip` (a name it lacks is refused, the
/// clip's joints listed).
JointMap readJointMap(const std::filesystem::path& path, const Clip& clip);

/// A clip retargeted to a skeleton.
struct Motion {
  double fps = 0;
  std::vector<body::Pose> poses;  ///< one per frame, relative to the fixed root
  /// The clip's root motion in our axes, for export: per frame, the root's rotation (relative to its rest) and its
  /// displacement from its rest position in metres (the clip's units scaled by rootScale).
  std::vector<Eigen::Matrix3d> rootRotations;
  Eigen::MatrixX3d rootTranslations;
  double rootScale = 1;  ///< metres per clip unit: our root-to-neck length over the clip's
  JointMap map;
  std::string source;     ///< the clip's file
  int clampedFrames = 0;  ///< frames clamped into the joint limits (BeyondLimits::Clamp)

  int frames() const { return static_cast<int>(poses.size()); }
};

/// Retargets `clip` to `skeleton` through `map`, whatever the clip's rest pose, axes, channel order and units:
/// - the clip's axes are aligned to ours from its rest pose (up: root to neck; left: right arm to left arm), to the
///   nearest quarter turn when within 10 degrees of one;
/// - each joint's world rotation relative to the clip's rest and to its root is applied to our joint; the rest poses
///   are taken to agree except where the upper arms point (an A-pose clip's arms are turned onto ours first, the
///   forearms with them); our local rotations follow;
/// - a frame beyond the joint limits is refused naming the frame and joint, or, with BeyondLimits::Clamp, clamped
///   and counted. An angle less than 1 degree beyond is the two skeletons' differing bones, not the motion: it is
///   clamped and not counted. Every pose returned is within the limits.
Motion retarget(const Clip& clip, const body::Skeleton& skeleton, const JointMap& map,
                body::BeyondLimits beyondLimits = body::BeyondLimits::Refuse);

/// `frames` (positions in the fixed-root frame the networks predict in, one matrix per frame of `motion`) moved by the
/// clip's root motion: turned about `rootPosition` (our skeleton's root at rest) and displaced, as the clip moves.
std::vector<Eigen::MatrixX3d> withRootMotion(const std::vector<Eigen::MatrixX3d>& frames, const Motion& motion,
                                             const Eigen::Vector3d& rootPosition);
/// The inverse of withRootMotion: positions in the clip's world (e.g. captured markers; NaN rows stay NaN) brought
/// into the fixed-root frame.
std::vector<Eigen::MatrixX3d> withoutRootMotion(const std::vector<Eigen::MatrixX3d>& frames, const Motion& motion,
                                                const Eigen::Vector3d& rootPosition);

/// Writes motion.json and poses.npy into `folder` (poses.npy first, motion.json last, each atomically).
void writeMotion(const std::filesystem::path& folder, const Motion& motion);
/// Reads a motion folder; InputError naming the file for a missing or malformed motion.json or poses.npy, a frame
/// count that disagrees, or a pose that is not a set of rotations. `beyondLimits` as everywhere: refuse or clamp.
Motion readMotion(const std::filesystem::path& folder, body::BeyondLimits beyondLimits = body::BeyondLimits::Refuse);

}  // namespace pixelcloth::motion
