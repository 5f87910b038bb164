#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace pixelcloth::body {

/// The 10 posable joints, in the order of the pose vector (DESIGN.md "Pose vector").
inline const std::array<std::string, 10> kPoseJoints = {"lower_back", "spine",     "spine1",     "neck",  "l_shoulder",
                                                        "l_arm",      "l_forearm", "r_shoulder", "r_arm", "r_forearm"};
/// Number of floats in a pose vector: 10 row-major 3x3 rotations.
inline constexpr int kPoseSize = 90;
/// Floats of a necktie's pose vector: the first four joints (lower_back, spine, spine1, neck), the centre line the tie
/// hangs from. Pose::fromLeading completes it with identities.
inline constexpr int kNecktiePoseSize = 36;

/// Range of motion of one posable joint: Euler angles in degrees about the joint's rest axes
/// (x: flexion / pitch, y: twist about the vertical, z: lateral bend), composed in the order
/// x, then z, then y (R = Ry * Rz * Rx), as in the paper's pose-sampling appendix.
struct JointLimits {
  Eigen::Vector3d lower;  ///< degrees (x, y, z)
  Eigen::Vector3d upper;  ///< degrees (x, y, z)
  std::string source;     ///< where the numbers come from
};

/// Rotation from Euler angles in degrees (x, y, z), composed x first, then z, then y: R = Ry * Rz * Rx.
Eigen::Matrix3d rotationFromEulerXZY(const Eigen::Vector3d& degrees);
/// Inverse of rotationFromEulerXZY, angles in degrees (x, y, z); exact for |z| < 90 degrees.
Eigen::Vector3d eulerXZYFromRotation(const Eigen::Matrix3d& rotation);

/// A kinematic tree in its rest T-pose: Y up, body facing +Z, the wearer's left on +X. Rest joint
/// frames are aligned with the world axes, so a pose is a set of local rotations relative to rest.
/// Joints: the 10 posable ones plus a fixed `root` (pelvis) and a fixed `head`.
struct Skeleton {
  std::vector<std::string> names;  ///< #J joint names
  std::vector<int> parents;        ///< #J parent index, -1 for the root; parents come before children
  Eigen::MatrixX3d positions;      ///< #J x 3 rest joint positions, metres
  Eigen::MatrixX3d boneEnds;       ///< #J x 3 where each joint's bone ends (its main child, or a tip for leaves)

  int numJoints() const { return static_cast<int>(names.size()); }
  /// Index of a joint by name; throws InputError listing the valid names when unknown.
  int index(const std::string& name) const;
  /// Skeleton indices of the 10 posable joints, in pose-vector order.
  std::array<int, 10> poseJointIndices() const;
  /// Throws InputError when names, parents, positions and bone ends are inconsistent.
  void validate(const std::string& context = "skeleton") const;
};

/// The names of the 12 joints of the built-in skeleton, in storage order.
const std::vector<std::string>& standardJointNames();
/// Parents of the standard joints (same order).
const std::vector<int>& standardJointParents();

/// Joint limits of a posable joint (by name), from AAOS "Joint Motion: Method of Measuring and
/// Recording" (1965) normal ranges, re-expressed relative to the T-pose; trunk ranges split evenly over
/// the three spine joints; clavicle ranges after Ludewig et al. (J Bone Joint Surg 2009). Right-side
/// joints mirror the left (y and z negated).
const JointLimits& jointLimits(const std::string& name);

/// Ten local rotations relative to the rest pose (DESIGN.md "Pose vector").
struct Pose {
  std::array<Eigen::Matrix3d, 10> rotations;  ///< in kPoseJoints order

  /// The rest pose (all identities).
  static Pose identity();
  /// From 90 floats (10 row-major 3x3); checks finiteness and that each block is a rotation
  /// (orthonormal within 1e-3, determinant +1). `context` prefixes error messages.
  static Pose fromVector(const Eigen::Ref<const Eigen::VectorXf>& values, const std::string& context = "pose");
  /// From the leading 9 k floats (the first k joints, 0 <= k <= 10: a necktie dataset stores 36, the spine and
  /// neck), every later joint at identity; checked as fromVector.
  static Pose fromLeading(const Eigen::Ref<const Eigen::VectorXf>& values, const std::string& context = "pose");
  /// From Euler angles (degrees, x y z per joint; 10 x 3), composed as rotationFromEulerXZY.
  static Pose fromEulerDegrees(const Eigen::Matrix<double, 10, 3>& degrees);
  Eigen::VectorXf toVector() const;  ///< 90 floats
  Eigen::Matrix<double, 10, 3> toEulerDegrees() const;
  /// True when every joint's Euler angles lie within its limits (with `slackDegrees` tolerance).
  bool withinLimits(double slackDegrees = 1e-6) const;
  /// The first Euler angle beyond its joint's limit (by more than `slackDegrees`), for a message: "joint 'l_arm':
  /// z = 120 degrees, beyond its limits -90 to 90 (AAOS ...)"; empty when every angle is within.
  std::string limitViolation(double slackDegrees = 0.05) const;
  /// Every joint's Euler angles clamped into its limits.
  Pose clampedToLimits() const;
};

/// World transforms of every joint for a pose: `rotations[j]` and `positions.row(j)`.
struct JointTransforms {
  std::vector<Eigen::Matrix3d> rotations;  ///< #J global rotations
  Eigen::MatrixX3d positions;              ///< #J x 3 posed joint positions, metres
};

/// Forward kinematics: global rotation G_j = G_parent * R_j and position
/// p_j = p_parent + G_parent * (rest_j - rest_parent). The root and head have no pose rotation.
JointTransforms forwardKinematics(const Skeleton& skeleton, const Pose& pose);

/// Linear blend skinning: v' = sum_j W(v, j) (G_j (v - rest_j) + p_j).
/// `restVertices` #V x 3, `weights` #V x #J (rows sum to 1). Returns #V x 3.
Eigen::MatrixX3d skin(const Skeleton& skeleton, const Eigen::MatrixX3d& restVertices, const Eigen::MatrixXd& weights,
                      const Pose& pose);

/// The T-pose with both upper arms lowered by `degrees` towards the body (an A-pose when positive).
Pose armsLowered(double degrees);

/// A pose whose Euler angles are drawn uniformly in [amount * lower, amount * upper] of each joint's limits
/// (every range contains 0, so amount = 0 is the rest pose and 1 the full range). Seeded, deterministic.
/// The paper's pose sampler (half-normal mixtures, azimuth / altitude / twist, pruning) lives in sim/.
Pose randomPose(std::uint64_t seed, double amount = 1.0);

}  // namespace pixelcloth::body
