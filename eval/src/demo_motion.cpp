// The demo's motion: a clip of its own, out as a GLB, in again through assimp, and through the patch decoders.
#include <Eigen/Geometry>
#include <cmath>

#include "pixelcloth/core/error.h"
#include "pixelcloth/eval/demo.h"
#include "pixelcloth/learn/prediction_inputs.h"
#include "pixelcloth/motion/clip.h"
#include "pixelcloth/motion/glb.h"
#include "pixelcloth/sim/pose_sampler.h"
#include "pixelcloth/stitch/stitcher.h"

namespace pixelcloth::eval {

namespace fs = std::filesystem;

DemoMotion runDemoMotion(const fs::path& report, const DemoPlan& plan) {
  DemoMotion out;
  const fs::path folder = report / "motion";
  out.clip = folder / "clip.glb";
  out.imported = folder / "imported";
  out.predicted = folder / "predicted";
  const data::DatasetFolder dataset(report / "dataset_tshirt");
  const body::Body body = data::loadDatasetBody(dataset);

  // Three seconds at 24 fps through four key poses from the paper's sampler (arms clear of the torso; Euler angles
  // eased between them stay inside the limits' box) and back to the first, the root turning 40 degrees and stepping
  // forward.
  constexpr int kKeys = 4, kFramesPerKey = 18;
  constexpr double kFps = 24;
  sim::PoseSamplerOptions sampling;
  sampling.seed = plan.seed + 1000;
  std::vector<Eigen::Matrix<double, 10, 3>> keys;
  for (const body::Pose& pose : sim::PoseSampler(body, sampling).sample(kKeys)) keys.push_back(pose.toEulerDegrees());
  keys.push_back(keys.front());
  motion::AnimatedScene scene;
  scene.body = &body;
  scene.fps = kFps;
  const int frames = kKeys * kFramesPerKey + 1;
  scene.rootTranslations.resize(frames, 3);
  for (int f = 0; f < frames; ++f) {
    const int k = std::min(f / kFramesPerKey, kKeys - 1);
    const double s = static_cast<double>(f - k * kFramesPerKey) / kFramesPerKey, eased = s * s * (3 - 2 * s);
    scene.poses.push_back(body::Pose::fromEulerDegrees((1 - eased) * keys[k] + eased * keys[k + 1]));
    const double t = static_cast<double>(f) / (frames - 1);
    scene.rootRotations.push_back(Eigen::AngleAxisd(40 * M_PI / 180 * t, Eigen::Vector3d::UnitY()).toRotationMatrix());
    scene.rootTranslations.row(f) << 0, 0, 0.3 * t;
  }
  motion::writeAnimatedGlb(out.clip, scene);
  out.keyPoses = kKeys;

  // In again as any clip comes in.
  const motion::Clip clip = motion::readClip(out.clip);
  out.motion = motion::retarget(clip, body.skeleton, motion::detectJointMap(clip));
  motion::writeMotion(out.imported, out.motion);
  PIXELCLOTH_CHECK(out.motion.frames() == frames,
                   out.clip.string() << ": " << out.motion.frames() << " frames imported of " << frames << " written");
  for (int f = 0; f < frames; ++f)
    for (int k = 0; k < 10; ++k)
      out.maxRetargetDegrees = std::max(
          out.maxRetargetDegrees,
          Eigen::AngleAxisd(out.motion.poses[f].rotations[k].transpose() * scene.poses[f].rotations[k]).angle() * 180 /
              M_PI);

  const learn::PredictionInputs inputs = learn::posesPredictionInputs(
      report / "model_patch", out.motion.poses, out.imported.string(), dataset, learn::Engine::OneDnn);
  const stitch::Stitcher mean(inputs.data.garment, stitch::StitchMode{}, nullptr);
  out.prediction = predictMotion(inputs, mean, out.motion, out.predicted,
                                 {{"model", "model_patch"}, {"motion", "motion/imported"}, {"stitch", "mean"}});
  return out;
}

}  // namespace pixelcloth::eval
