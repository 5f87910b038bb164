// The demo's motion (eval::runDemoMotion) drawn: the clip's strip, the garment on the moving body, the temporal
// measures, and the files other tools read.
#include <iomanip>
#include <sstream>

#include "pixelcloth/core/image.h"
#include "pixelcloth/viz/demo.h"
#include "pixelcloth/viz/motion_pictures.h"
#include "pixelcloth/viz/pictures.h"

namespace pixelcloth::viz {

void demoMotion(Report& report, const body::Body& body, const eval::DemoMotion& demo) {
  const eval::MotionPrediction& p = demo.prediction;
  core::writePng(demo.imported / "motion.png", renderPoseStrip(body, demo.motion.poses, demo.motion.fps));
  const core::Mesh garment = data::datasetGarment(data::readDatasetInfo(report.folder() / "dataset_tshirt")).mesh;
  writeSequencePictures(demo.predicted, body.mesh.F, garment, p);
  const eval::MotionPrediction& r = demo.reconstruction;
  writeSequencePictures(demo.reconstructed, body.mesh.F, garment, r);
  report.json()["motion"] = {{"frames", p.frames},
                             {"fps", p.fps},
                             {"key_poses", demo.keyPoses},
                             {"joint_map", demo.motion.map.name},
                             {"max_retarget_error_deg", demo.maxRetargetDegrees},
                             {"prediction_ms_per_frame", 1000 * p.predictSeconds / p.frames},
                             {"metrics", p.metrics.toJson()},
                             {"files", p.files},
                             {"reconstruction",
                              {{"markers", demo.markerCount},
                               {"dropout", demo.markerDropout},
                               {"base_error_cm", demo.baseErrorCm},
                               {"error_cm", demo.reconstructionErrorCm},
                               {"ms_per_frame", 1000 * r.predictSeconds / r.frames},
                               {"metrics", r.metrics.toJson()}}}};
  std::ostringstream text;
  text << std::fixed << std::setprecision(2) << "A motion of the demo's own (motion/): " << p.frames << " frames at "
       << std::setprecision(0) << p.fps << std::setprecision(2) << " fps through " << demo.keyPoses
       << " key poses from the paper's sampler, eased into one another, the root turning 40 degrees and "
          "stepping forward. It is written as an animated GLB the way other tools write clips (motion/clip.glb), "
          "and imported back through assimp like any clip (pixelcloth motion import): the "
       << demo.motion.map.name << " joint map was recognised, and the retargeted poses are within " << std::defaultfloat
       << std::setprecision(2) << demo.maxRetargetDegrees << std::fixed
       << " degrees of the ones written. The demo's 28 patch decoders then predicted every frame in "
       << 1000 * p.predictSeconds / p.frames
       << " ms a frame (pixelcloth predict --motion). Temporal measures: the garment's jitter, the mean of |x(t+1) - "
          "2x(t) + x(t-1)| over its vertices, is "
       << p.metrics.meanGarmentJitterCm() << " cm against the body's " << p.metrics.meanBodyJitterCm()
       << " cm; garment vertices lie inside the body in " << p.metrics.framesWithInside() << " of " << p.frames
       << " frames (at most " << p.metrics.toJson()["inside_body"]["max_depth_cm"].get<double>()
       << " cm deep). These decoders trained for a few epochs on a few dozen shirts, so the garment is rough: the "
          "point is the path from clip to animation. The files in motion/predicted/ play in other tools: "
          "animation.glb (the body skinned on its animated joints, the garment as one morph target per frame), "
          "garment.pc2 and body.pc2 with garment.obj and body.obj (Blender's Mesh Cache modifier), and the OBJ "
          "frames. The seam gap, how far apart the patch decoders put the vertices they share on the cage curves "
          "before blending, is "
       << p.metrics.meanSeamGapCm() << " cm. Then that garment as a capture system would see it: its "
       << demo.markerCount << " markers in every frame, in the clip's world, with " << std::setprecision(0)
       << 100 * demo.markerDropout << std::setprecision(2)
       << "% of the curve markers lost in each (motion/markers/trajectories.npy; pixelcloth markers --pc2). Rebuilt "
          "frame by frame and refined by the residual patch decoders (pixelcloth reconstruct --markers-sequence "
          "--model) in "
       << 1000 * r.predictSeconds / r.frames << " ms a frame, they give back the garment they were taken from to "
       << demo.reconstructionErrorCm << " cm (the markers alone: " << demo.baseErrorCm << " cm), with a jitter of "
       << r.metrics.meanGarmentJitterCm() << " cm (motion/reconstructed/).";
  report.section("Motion", text.str(),
                 {"motion/imported/motion.png", "motion/predicted/strip.png", "motion/predicted/temporal.png",
                  "motion/reconstructed/strip.png", "motion/reconstructed/temporal.png"});
}

}  // namespace pixelcloth::viz
