#include "pixelcloth/sim/pose_sampler.h"

#include <algorithm>
#include <cmath>

#include "pixelcloth/core/error.h"

namespace pixelcloth::sim {

namespace {
constexpr double kDegree = M_PI / 180.0;

bool isCentreLine(const std::string& joint) {
  return joint == "lower_back" || joint == "spine" || joint == "spine1" || joint == "neck";
}

/// Number of triangles of (V, faces) crossed by the ray from p along +z (direction = 1) or -z (-1).
int crossings(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const std::vector<int>& faces,
              const Eigen::Vector3d& p, double direction) {
  int count = 0;
  for (int f : faces) {
    Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    // Cheap reject: the ray is a vertical line in (x, y).
    if (p.x() < std::min({a.x(), b.x(), c.x()}) || p.x() > std::max({a.x(), b.x(), c.x()}) ||
        p.y() < std::min({a.y(), b.y(), c.y()}) || p.y() > std::max({a.y(), b.y(), c.y()}))
      continue;
    // Barycentric coordinates of (p.x, p.y) in the triangle projected on the xy plane.
    double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(det) < 1e-16) continue;
    double u = ((p.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (p.y() - a.y())) / det;
    double v = ((b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y())) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    double z = a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
    if ((z - p.z()) * direction > 0) ++count;
  }
  return count;
}
}  // namespace

void PoseSamplerOptions::validate() const {
  PIXELCLOTH_CHECK(centreSpread > 0 && centreSpread <= 2,
                   "pose sampler: centre spread must be in (0, 2], got " << centreSpread);
  PIXELCLOTH_CHECK(maxAttempts > 0, "pose sampler: max attempts must be positive");
}

PoseSampler::PoseSampler(const body::Body& body, const PoseSamplerOptions& options)
    : body_(body), options_(options), rng_(options.seed) {
  options_.validate();
  for (const body::BodyPart& part : body.parts)
    if (part.name == "torso") torsoFaces_ = part.faces;
  PIXELCLOTH_CHECK(!options.prune || !torsoFaces_.empty(), "pose sampler: the body has no 'torso' part to prune with");
}

body::Pose PoseSampler::draw() {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Matrix<double, 10, 3> degrees;
  for (int k = 0; k < 10; ++k) {
    const std::string& joint = body::kPoseJoints[k];
    const body::JointLimits& limits = body::jointLimits(joint);
    for (int axis = 0; axis < 3; ++axis) {
      double lo = limits.lower[axis], hi = limits.upper[axis];
      double angle = 0;
      if (lo == hi) {
        angle = lo;
      } else if (isCentreLine(joint)) {
        double side = unit(rng_) < 0.5 ? lo : hi;  // which half-normal of the mixture
        angle = std::min(std::abs(normal(rng_)) * options_.centreSpread, 1.0) * side;
      } else if (axis == 2) {  // altitude: uniform in sine space
        double s = std::sin(lo * kDegree) + unit(rng_) * (std::sin(hi * kDegree) - std::sin(lo * kDegree));
        angle = std::asin(std::clamp(s, -1.0, 1.0)) / kDegree;
      } else {  // azimuth (y) and twist (x): uniform
        angle = lo + unit(rng_) * (hi - lo);
      }
      degrees(k, axis) = angle;
    }
  }
  return body::Pose::fromEulerDegrees(degrees);
}

bool PoseSampler::armInsideTorso(const body::Pose& pose) const {
  if (torsoFaces_.empty()) return false;
  const body::Skeleton& s = body_.skeleton;
  Eigen::MatrixX3d V = body_.posedVertices(pose);
  body::JointTransforms t = body::forwardKinematics(s, pose);
  for (const char* side : {"l", "r"}) {
    int arm = s.index(std::string(side) + "_arm"), fore = s.index(std::string(side) + "_forearm");
    Eigen::Vector3d shoulder = t.positions.row(arm).transpose(), elbow = t.positions.row(fore).transpose();
    Eigen::Vector3d tip = t.rotations[fore] * (s.boneEnds.row(fore) - s.positions.row(fore)).transpose() + elbow;
    for (int i = 1; i <= 16; ++i) {
      double u = i / 16.0;
      Eigen::Vector3d p = u <= 0.5 ? Eigen::Vector3d(shoulder + 2 * u * (elbow - shoulder))
                                   : Eigen::Vector3d(elbow + (2 * u - 1) * (tip - elbow));
      if ((p - shoulder).norm() < 0.15) continue;  // near the shoulder the torso part overlaps the arm
      if (crossings(V, body_.mesh.F, torsoFaces_, p, 1.0) % 2 == 1 &&
          crossings(V, body_.mesh.F, torsoFaces_, p, -1.0) % 2 == 1)
        return true;
    }
  }
  return false;
}

body::Pose PoseSampler::next() {
  for (int attempt = 0; attempt < options_.maxAttempts; ++attempt) {
    body::Pose pose = draw();
    if (options_.prune && armInsideTorso(pose)) {
      ++stats_.rejectedArmInsideTorso;
      continue;
    }
    ++stats_.accepted;
    return pose;
  }
  PIXELCLOTH_FAIL("pose sampler: " << options_.maxAttempts << " poses in a row had an arm inside the torso");
}

std::vector<body::Pose> PoseSampler::sample(int count) {
  std::vector<body::Pose> poses;
  poses.reserve(count);
  for (int i = 0; i < count; ++i) poses.push_back(next());
  return poses;
}

}  // namespace pixelcloth::sim
