#include "pixelcloth/eval/sampled_motion.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "pixelcloth/core/error.h"
#include "pixelcloth/sim/pose_sampler.h"

namespace pixelcloth::eval {

motion::AnimatedScene sampledMotion(const body::Body& body, int keys, int framesPerKey, double fps,
                                    std::uint64_t seed) {
  PIXELCLOTH_CHECK(keys >= 1 && framesPerKey >= 1 && fps > 0,
                   "sampled motion: " << keys << " keys of " << framesPerKey << " frames at " << fps << " fps");
  sim::PoseSamplerOptions sampling;
  sampling.seed = seed;
  std::vector<Eigen::Matrix<double, 10, 3>> key;
  for (const body::Pose& pose : sim::PoseSampler(body, sampling).sample(keys)) key.push_back(pose.toEulerDegrees());
  key.push_back(key.front());
  motion::AnimatedScene scene;
  scene.body = &body;
  scene.fps = fps;
  const int frames = keys * framesPerKey + 1;
  scene.rootTranslations.resize(frames, 3);
  for (int f = 0; f < frames; ++f) {
    const int k = std::min(f / framesPerKey, keys - 1);
    const double s = static_cast<double>(f - k * framesPerKey) / framesPerKey, eased = s * s * (3 - 2 * s);
    scene.poses.push_back(body::Pose::fromEulerDegrees((1 - eased) * key[k] + eased * key[k + 1]));
    const double t = static_cast<double>(f) / (frames - 1);
    scene.rootRotations.push_back(Eigen::AngleAxisd(40 * M_PI / 180 * t, Eigen::Vector3d::UnitY()).toRotationMatrix());
    scene.rootTranslations.row(f) << 0, 0, 0.3 * t;
  }
  return scene;
}

}  // namespace pixelcloth::eval
