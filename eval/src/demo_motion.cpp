// The demo's motion: a clip of its own, out as a GLB, in again through assimp, and through the patch decoders.
#include <Eigen/Geometry>
#include <algorithm>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/eval/demo.h"
#include "pixelcloth/eval/sampled_motion.h"
#include "pixelcloth/learn/prediction_inputs.h"
#include "pixelcloth/learn/spaces.h"
#include "pixelcloth/motion/clip.h"
#include "pixelcloth/motion/glb.h"
#include "pixelcloth/motion/trajectories.h"
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

  // Three seconds at 24 fps through four key poses from the paper's sampler and back to the first.
  constexpr int kKeys = 4, kFramesPerKey = 18;
  const motion::AnimatedScene scene = sampledMotion(body, kKeys, kFramesPerKey, 24, plan.seed + 1000);
  const int frames = static_cast<int>(scene.poses.size());
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
  out.prediction = predictMotion(
      inputs, mean, out.motion, out.predicted,
      {{"model", "model_patch"}, {"motion", "motion/imported"}, {"stitch", "mean"}, {"dataset", "dataset_tshirt"}});

  // The predicted garment as markers in the clip's world, as pixelcloth markers --pc2 takes them from garment.pc2.
  out.markers = folder / "markers";
  out.reconstructed = folder / "reconstructed";
  learn::PredictionInputs residual = learn::posesPredictionInputs(
      report / "model_residual_patch", out.motion.poses, out.imported.string(), dataset, learn::Engine::OneDnn);
  const garment::Garment& garment = residual.data.garment;
  const cage::Cage cage = cage::garmentCage(garment);
  const cage::MarkerSet definition = cage::defineMarkers(garment, cage);  // the demo's bases' spacing
  out.markerCount = static_cast<int>(definition.markers.size());
  const Eigen::Vector3d root = body.skeleton.positions.row(body.skeleton.index("root")).transpose();
  motion::MarkerTrajectories trajectories =
      markerTrajectories(definition, cage, motion::withRootMotion(out.prediction.garment, out.motion, root),
                         {0, out.markerDropout, plan.seed});
  trajectories.source = (out.markers / "trajectories.npy").string();
  cage::writeMarkers(out.markers / "markers.json", definition);
  motion::writeMarkerTrajectories(trajectories.source, trajectories);

  // In again as pixelcloth reconstruct --markers-sequence --model reads them.
  const double baseSeconds =
      addTrajectoryBases(residual, body, definition, "motion/markers/markers.json", trajectories, out.motion, 0);
  out.reconstruction = predictMotion(residual, mean, out.motion, out.reconstructed,
                                     {{"model", "model_residual_patch"},
                                      {"markers", "motion/markers/markers.json"},
                                      {"markers_sequence", "motion/markers/trajectories.npy"},
                                      {"dataset", "dataset_tshirt"}});
  out.reconstruction.predictSeconds += baseSeconds;
  for (int f = 0; f < frames; ++f) {
    const Eigen::MatrixX3d base =
        learn::positionsFromValues(residual.data.space, residual.data.frames[f], residual.data.base[f]);
    out.baseErrorCm += core::meanVertexErrorCm(base, out.prediction.garment[f]) / frames;
    out.reconstructionErrorCm +=
        core::meanVertexErrorCm(out.reconstruction.garment[f], out.prediction.garment[f]) / frames;
  }
  return out;
}

}  // namespace pixelcloth::eval
