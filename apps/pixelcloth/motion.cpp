// pixelcloth motion import: a motion-capture clip (BVH, FBX, glTF/GLB, Collada) retargeted to the body's joints.
#include "pixelcloth/motion/motion.h"

#include <iostream>
#include <memory>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/viz/pictures.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct MotionImportArgs {
  std::string clip, body, map, out;
  double fps = 0;
  int animation = 0;
};

void runMotionImport(const MotionImportArgs& args) {
  core::checkOutputFolder(args.out);
  core::checkRunFolder(args.out, {"motion.json", {}, "a motion"});
  motion::ClipOptions options;
  options.fps = args.fps;
  options.animation = args.animation;
  const motion::Clip clip = motion::readClip(args.clip, options);
  const motion::JointMap map = args.map.empty() ? motion::detectJointMap(clip) : motion::readJointMap(args.map, clip);
  const body::Body body = args.body.empty() ? body::makeMannequin() : body::loadBody(args.body);
  const motion::Motion motion = motion::retarget(clip, body.skeleton, map, poseLimits());
  motion::writeMotion(args.out, motion);
  core::writePng(std::filesystem::path(args.out) / "motion.png", viz::renderPoseStrip(body, motion.poses, motion.fps));
  std::cout << "motion import: " << motion.frames() << " frames at " << motion.fps << " fps (" << map.name
            << " joint map";
  if (motion.clampedFrames > 0) std::cout << ", " << motion.clampedFrames << " frames clamped into the joint limits";
  std::cout << ") -> " << args.out << "/{motion.json, poses.npy, motion.png}\n";
}
}  // namespace

void registerMotion(CLI::App& app) {
  CLI::App* verb = app.add_subcommand("motion", "Motion clips: import one for `pose --motion` and `predict --motion`");
  verb->require_subcommand(1);
  auto args = std::make_shared<MotionImportArgs>();
  CLI::App* import = verb->add_subcommand(
      "import",
      "Read a motion-capture clip through assimp (BVH, FBX, glTF/GLB, Collada) and retarget it to the body's 10 pose "
      "joints by name (CMU, Mixamo or SMPL naming, or --map), whatever its rest pose, axes, channel order and units. "
      "Writes motion.json (fps, frames, joint map, root motion), poses.npy (frames x 90 float32) and motion.png. A "
      "frame beyond the joint limits is refused unless --clamp-to-limits");
  import->add_option("clip", args->clip, "The clip file")->required();
  import->add_option("--body", args->body, "Body folder from `pixelcloth body` (default: the built-in mannequin)");
  import->add_option("--map", args->map,
                     "Joint map JSON naming the clip joint of each of ours: {\"root\": \"Hips\", \"lower_back\": ..., "
                     "\"r_forearm\": ..., \"ends\": {\"l_forearm\": \"LeftHand\"}}");
  import->add_option("--fps", args->fps, "Frames per second to sample at (default: the clip's own key rate, else 30)")
      ->check(CLI::Range(1.0, 1000.0));
  import->add_option("--animation", args->animation, "Which animation of the file, by index")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  import->add_option("--out", args->out, "Output motion folder")->required();
  import->callback([args] { runMotionImport(*args);
});
}  // namespace pixelcloth::apps

}  // namespace pixelcloth::apps
