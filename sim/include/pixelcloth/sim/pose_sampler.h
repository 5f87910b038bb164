#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/body/skeleton.h"

namespace pixelcloth::sim {

/// Options of the paper's pose sampler (appendix, "pose sampling").
struct PoseSamplerOptions {
  std::uint64_t seed = 0;
  /// Centre line (lower_back, spine, spine1, neck): each angle is a mixture of two half-normals, one on each side of
  /// 0, chosen with equal probability, each with standard deviation `centreSpread` times that side's joint limit,
  /// clamped to the limit (the ranges are asymmetric: flexion 80 vs extension 25 degrees).
  double centreSpread = 0.5;
  /// Reject poses whose arm sample points fall inside the torso.
  bool prune = true;
  /// Give up (InputError) after this many rejections in a row.
  int maxAttempts = 1000;
  void validate() const;
};

/// Counts of the sampler's decisions.
struct PoseSamplerStats {
  int accepted = 0;
  int rejectedArmInsideTorso = 0;
};

/// Draws poses as the paper's appendix does. Centre-line joints: half-normal mixtures (see options). Shoulders
/// (clavicles), arms and forearms: azimuth (y) uniform, altitude (z) uniform in sine space (so the bone's direction
/// is uniform on its patch of the sphere), twist (x) uniform, each within the joint's limits; composed in the order
/// x, z, y (R = Ry Rz Rx, body::rotationFromEulerXZY). Pruning: sample points along each posed upper arm and forearm
/// (beyond 15 cm from the shoulder joint) must not lie inside the posed torso part of the body (ray parity against
/// the torso's faces along +z and -z). Seeded: the same seed gives the same poses.
class PoseSampler {
 public:
  PoseSampler(const body::Body& body, const PoseSamplerOptions& options = {});

  /// The next accepted pose.
  body::Pose next();
  /// `count` accepted poses.
  std::vector<body::Pose> sample(int count);
  /// A pose drawn without pruning (the raw distribution).
  body::Pose draw();
  /// True when a sample point of either arm lies inside the torso in this pose.
  bool armInsideTorso(const body::Pose& pose) const;

  const PoseSamplerStats& stats() const { return stats_; }

 private:
  const body::Body& body_;
  PoseSamplerOptions options_;
  std::mt19937_64 rng_;
  PoseSamplerStats stats_;
  std::vector<int> torsoFaces_;
};

}  // namespace pixelcloth::sim
