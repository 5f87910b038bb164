#include "pixelcloth/body/skeleton.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>

#include "pixelcloth/core/error.h"

namespace pixelcloth::body {

using namespace core;

namespace {
constexpr double kDegree = M_PI / 180.0;

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}
}  // namespace

Eigen::Matrix3d rotationFromEulerXZY(const Eigen::Vector3d& degrees) {
  Eigen::Matrix3d rx = Eigen::AngleAxisd(degrees.x() * kDegree, Eigen::Vector3d::UnitX()).toRotationMatrix();
  Eigen::Matrix3d ry = Eigen::AngleAxisd(degrees.y() * kDegree, Eigen::Vector3d::UnitY()).toRotationMatrix();
  Eigen::Matrix3d rz = Eigen::AngleAxisd(degrees.z() * kDegree, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return ry * rz * rx;
}

Eigen::Vector3d eulerXZYFromRotation(const Eigen::Matrix3d& r) {
  // R = Ry Rz Rx: R(1,0) = sin z, R(1,1) = cos z cos x, R(1,2) = -cos z sin x,
  // R(0,0) = cos y cos z, R(2,0) = -sin y cos z.
  double z = std::asin(std::clamp(r(1, 0), -1.0, 1.0));
  double x = std::atan2(-r(1, 2), r(1, 1));
  double y = std::atan2(-r(2, 0), r(0, 0));
  return Eigen::Vector3d(x, y, z) / kDegree;
}

const std::vector<std::string>& standardJointNames() {
  static const std::vector<std::string> names = {"root",      "lower_back", "spine",      "spine1",
                                                 "neck",      "head",       "l_shoulder", "l_arm",
                                                 "l_forearm", "r_shoulder", "r_arm",      "r_forearm"};
  return names;
}

const std::vector<int>& standardJointParents() {
  static const std::vector<int> parents = {-1, 0, 1, 2, 3, 4, 3, 6, 7, 3, 9, 10};
  return parents;
}

int Skeleton::index(const std::string& name) const {
  for (int j = 0; j < numJoints(); ++j)
    if (names[j] == name) return j;
  PIXELCLOTH_FAIL("unknown joint '" << name << "'; expected one of: " << joinNames(names));
}

std::array<int, 10> Skeleton::poseJointIndices() const {
  std::array<int, 10> indices{};
  for (int k = 0; k < 10; ++k) indices[k] = index(kPoseJoints[k]);
  return indices;
}

void Skeleton::validate(const std::string& context) const {
  const int n = numJoints();
  PIXELCLOTH_CHECK(n > 0, context << ": no joints");
  PIXELCLOTH_CHECK(static_cast<int>(parents.size()) == n && positions.rows() == n && boneEnds.rows() == n,
                   context << ": " << n << " names but " << parents.size() << " parents, " << positions.rows()
                           << " positions and " << boneEnds.rows() << " bone ends");
  int roots = 0;
  for (int j = 0; j < n; ++j) {
    PIXELCLOTH_CHECK(parents[j] < j, context << ": joint '" << names[j] << "' has parent " << parents[j]
                                             << "; parents must come before their children");
    roots += parents[j] < 0;
    PIXELCLOTH_CHECK(positions.row(j).allFinite() && boneEnds.row(j).allFinite(),
                     context << ": joint '" << names[j] << "' has a non-finite position");
  }
  PIXELCLOTH_CHECK(roots == 1, context << ": expected exactly one root joint, found " << roots);
  for (const auto& name : kPoseJoints) index(name);
}

const JointLimits& jointLimits(const std::string& name) {
  // Degrees (x, y, z) relative to the T-pose. See the header for the sources. For the left arm in
  // the T-pose (along +x): +z raises it, -y swings it forward, x twists it.
  static const std::string aaos = "AAOS normal range of motion (1965), relative to the T-pose";
  static const std::string trunk =
      "AAOS thoracolumbar range (flexion 80, extension 25, lateral 35, rotation 45), split over 3 joints";
  static const std::string clavicle = "Ludewig et al. 2009, sternoclavicular elevation / retraction";
  static const std::map<std::string, JointLimits> limits = [] {
    std::map<std::string, JointLimits> m;
    JointLimits spine{{-25.0 / 3, -15, -35.0 / 3}, {80.0 / 3, 15, 35.0 / 3}, trunk};
    m["lower_back"] = spine;
    m["spine"] = spine;
    m["spine1"] = spine;
    m["neck"] = {
        {-45, -60, -45}, {45, 60, 45}, aaos + " (cervical: flexion 45, extension 45, lateral 45, rotation 60)"};
    m["l_shoulder"] = {{0, -20, -10}, {0, 20, 30}, clavicle};
    m["l_arm"] = {{-90, -135, -90},
                  {70, 45, 90},
                  aaos +
                      " (shoulder: abduction 180 = T-pose +90, adduction to the side -90, horizontal flexion "
                      "135, horizontal extension 45, rotation 70 / 90)"};
    m["l_forearm"] = {{-80, -150, 0}, {80, 0, 0}, aaos + " (elbow flexion 150, pronation / supination 80)"};
    for (const char* side : {"shoulder", "arm", "forearm"}) {
      JointLimits right = m[std::string("l_") + side];
      // Mirror through the x = 0 plane: y and z change sign, so the bounds swap.
      for (int axis : {1, 2}) {
        double lo = right.lower[axis], hi = right.upper[axis];
        right.lower[axis] = -hi;
        right.upper[axis] = -lo;
      }
      right.source += " (mirrored for the right side)";
      m[std::string("r_") + side] = right;
    }
    return m;
  }();
  auto it = limits.find(name);
  PIXELCLOTH_CHECK(it != limits.end(), "no joint limits for '" << name
                                                               << "'; posable joints are lower_back, spine, "
                                                                  "spine1, neck, l_shoulder, l_arm, l_forearm, "
                                                                  "r_shoulder, r_arm, r_forearm");
  return it->second;
}

Pose Pose::identity() {
  Pose pose;
  pose.rotations.fill(Eigen::Matrix3d::Identity());
  return pose;
}

Pose Pose::fromVector(const Eigen::Ref<const Eigen::VectorXf>& values, const std::string& context) {
  PIXELCLOTH_CHECK(values.size() == kPoseSize,
                   context << ": a pose has " << kPoseSize << " numbers (10 joints x 3x3), found " << values.size());
  Pose pose;
  for (int k = 0; k < 10; ++k) {
    Eigen::Matrix3d r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        float v = values[9 * k + 3 * i + j];
        PIXELCLOTH_CHECK(std::isfinite(v), context << ": joint '" << kPoseJoints[k] << "' has a non-finite entry");
        r(i, j) = v;
      }
    double orthogonality = (r * r.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    PIXELCLOTH_CHECK(orthogonality < 1e-3 && r.determinant() > 0,
                     context << ": joint '" << kPoseJoints[k] << "' is not a rotation matrix (|R R^T - I| = "
                             << orthogonality << ", det = " << r.determinant() << ")");
    // Re-orthonormalise float input so skinning stays rigid.
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
    pose.rotations[k] = svd.matrixU() * svd.matrixV().transpose();
  }
  return pose;
}

Pose Pose::fromLeading(const Eigen::Ref<const Eigen::VectorXf>& values, const std::string& context) {
  PIXELCLOTH_CHECK(
      values.size() % 9 == 0 && values.size() <= kPoseSize,
      context << ": a pose has 9 numbers per joint for up to 10 joints (" << kPoseSize << "), found " << values.size());
  Eigen::VectorXf full = identity().toVector();
  full.head(values.size()) = values;
  return fromVector(full, context);
}

Pose Pose::fromEulerDegrees(const Eigen::Matrix<double, 10, 3>& degrees) {
  Pose pose;
  for (int k = 0; k < 10; ++k) pose.rotations[k] = rotationFromEulerXZY(degrees.row(k).transpose());
  return pose;
}

Eigen::VectorXf Pose::toVector() const {
  Eigen::VectorXf values(kPoseSize);
  for (int k = 0; k < 10; ++k)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) values[9 * k + 3 * i + j] = static_cast<float>(rotations[k](i, j));
  return values;
}

Eigen::Matrix<double, 10, 3> Pose::toEulerDegrees() const {
  Eigen::Matrix<double, 10, 3> degrees;
  for (int k = 0; k < 10; ++k) degrees.row(k) = eulerXZYFromRotation(rotations[k]).transpose();
  return degrees;
}

bool Pose::withinLimits(double slackDegrees) const {
  Eigen::Matrix<double, 10, 3> degrees = toEulerDegrees();
  for (int k = 0; k < 10; ++k) {
    const JointLimits& limits = jointLimits(kPoseJoints[k]);
    for (int a = 0; a < 3; ++a) {
      if (degrees(k, a) < limits.lower[a] - slackDegrees || degrees(k, a) > limits.upper[a] + slackDegrees)
        return false;
    }
  }
  return true;
}

std::string Pose::limitViolation(double slackDegrees) const {
  const Eigen::Matrix<double, 10, 3> degrees = toEulerDegrees();
  for (int k = 0; k < 10; ++k) {
    const JointLimits& limits = jointLimits(kPoseJoints[k]);
    for (int a = 0; a < 3; ++a)
      if (degrees(k, a) < limits.lower[a] - slackDegrees || degrees(k, a) > limits.upper[a] + slackDegrees) {
        std::ostringstream text;
        text << "joint '" << kPoseJoints[k] << "': " << "xyz"[a] << " = " << degrees(k, a)
             << " degrees, beyond its limits " << limits.lower[a] << " to " << limits.upper[a] << " ("
             << limits.source << "; Euler angles composed x, then z, then y)";
        return text.str();
      }
  }
  return "";
}

Pose Pose::clampedToLimits() const {
  Eigen::Matrix<double, 10, 3> degrees = toEulerDegrees();
  for (int k = 0; k < 10; ++k) {
    const JointLimits& limits = jointLimits(kPoseJoints[k]);
    for (int a = 0; a < 3; ++a) degrees(k, a) = std::clamp(degrees(k, a), limits.lower[a], limits.upper[a]);
  }
  return fromEulerDegrees(degrees);
}

JointTransforms forwardKinematics(const Skeleton& skeleton, const Pose& pose) {
  const int n = skeleton.numJoints();
  std::vector<Eigen::Matrix3d> local(n, Eigen::Matrix3d::Identity());
  std::array<int, 10> poseJoints = skeleton.poseJointIndices();
  for (int k = 0; k < 10; ++k) local[poseJoints[k]] = pose.rotations[k];
  JointTransforms out;
  out.rotations.resize(n);
  out.positions.resize(n, 3);
  for (int j = 0; j < n; ++j) {
    int p = skeleton.parents[j];
    if (p < 0) {
      out.rotations[j] = local[j];
      out.positions.row(j) = skeleton.positions.row(j);
    } else {
      out.rotations[j] = out.rotations[p] * local[j];
      Eigen::Vector3d offset = (skeleton.positions.row(j) - skeleton.positions.row(p)).transpose();
      out.positions.row(j) = out.positions.row(p) + (out.rotations[p] * offset).transpose();
    }
  }
  return out;
}

Eigen::MatrixX3d skin(const Skeleton& skeleton, const Eigen::MatrixX3d& restVertices, const Eigen::MatrixXd& weights,
                      const Pose& pose) {
  PIXELCLOTH_CHECK(weights.rows() == restVertices.rows() && weights.cols() == skeleton.numJoints(),
                   "skin: weights are " << weights.rows() << " x " << weights.cols() << ", expected "
                                        << restVertices.rows() << " x " << skeleton.numJoints());
  JointTransforms transforms = forwardKinematics(skeleton, pose);
  const int n = skeleton.numJoints();
  // Affine map per joint, x -> A_j x + t_j, blended per vertex.
  std::vector<Eigen::Matrix3d> a(n);
  std::vector<Eigen::Vector3d> t(n);
  for (int j = 0; j < n; ++j) {
    a[j] = transforms.rotations[j];
    t[j] = transforms.positions.row(j).transpose() - a[j] * skeleton.positions.row(j).transpose();
  }
  Eigen::MatrixX3d posed(restVertices.rows(), 3);
  for (int v = 0; v < restVertices.rows(); ++v) {
    Eigen::Matrix3d blendA = Eigen::Matrix3d::Zero();
    Eigen::Vector3d blendT = Eigen::Vector3d::Zero();
    for (int j = 0; j < n; ++j) {
      double w = weights(v, j);
      if (w == 0) continue;
      blendA += w * a[j];
      blendT += w * t[j];
    }
    posed.row(v) = (blendA * restVertices.row(v).transpose() + blendT).transpose();
  }
  return posed;
}

Pose armsLowered(double degrees) {
  Eigen::Matrix<double, 10, 3> e = Eigen::Matrix<double, 10, 3>::Zero();
  e(5, 2) = -degrees;  // l_arm: -z lowers the left arm
  e(8, 2) = degrees;   // r_arm mirrors it
  return Pose::fromEulerDegrees(e);
}

Pose randomPose(std::uint64_t seed, double amount) {
  PIXELCLOTH_CHECK(amount >= 0 && amount <= 1, "random pose: amount must be in [0, 1], got " << amount);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::Matrix<double, 10, 3> degrees;
  for (int k = 0; k < 10; ++k) {
    const JointLimits& limits = jointLimits(kPoseJoints[k]);
    for (int a = 0; a < 3; ++a) {
      double lo = amount * limits.lower[a], hi = amount * limits.upper[a];
      degrees(k, a) = lo + (hi - lo) * unit(rng);
    }
  }
  return Pose::fromEulerDegrees(degrees);
}

}  // namespace pixelcloth::body
