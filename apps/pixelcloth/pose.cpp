// pixelcloth pose: skin a body folder into given or random poses.
#include <memory>

#include "pixelcloth/body/body.h"
#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/motion/motion.h"
#include "pixelcloth/sim/pose_sampler.h"
#include "pixelcloth/viz/pictures.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct PoseArgs {
  std::string body;
  std::string pose;
  std::string motion;
  int random = 0;
  std::uint64_t seed = 0;
  std::string out;
};

void runPose(const PoseArgs& args) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  PIXELCLOTH_CHECK(!args.pose.empty() + !args.motion.empty() + (args.random != 0) == 1,
                   "pose: give one of --pose POSES.json, --motion M/ or --random N (with --seed S)");
  PIXELCLOTH_CHECK(args.random >= 0 && args.random <= 10000,
                   "pose: --random must be in [1, 10000], got " << args.random);
  pixelcloth::core::checkRunFolder(args.out, {"", {}, "posed bodies"});
  Body body = loadBody(args.body);
  std::vector<Pose> poses;
  nlohmann::json info = {{"body", args.body}};
  if (!args.pose.empty()) {
    poses = readPoses(args.pose, poseLimits());
    info["poses"] = args.pose;
  } else if (!args.motion.empty()) {
    const motion::Motion motion = motion::readMotion(args.motion, poseLimits());
    poses = motion.poses;
    info["motion"] = args.motion;
    info["fps"] = motion.fps;
  } else {
    sim::PoseSamplerOptions options;
    options.seed = args.seed;
    sim::PoseSampler sampler(body, options);
    poses = sampler.sample(args.random);
    PIXELCLOTH_INFO("pose: " << sampler.stats().rejectedArmInsideTorso << " drawn poses rejected (an arm inside the "
                             << "torso) for " << args.random << " kept");
    info["seed"] = args.seed;
    info["sampler"] = "appendix";
  }
  writePosedBodies(args.out, body, poses, info);
  PIXELCLOTH_INFO("pose: " << poses.size() << " posed meshes -> " << args.out
                           << "/{posed_NNN.obj, poses.json, poses.npy, posed.png}");
}
}  // namespace

void registerPose(CLI::App& app) {
  auto args = std::make_shared<PoseArgs>();
  CLI::App* verb = app.add_subcommand("pose", "Pose a body folder by linear blend skinning: posed OBJs and a picture");
  verb->add_option("--body", args->body, "Body folder written by 'pixelcloth body'")->required();
  verb->add_option("--pose", args->pose,
                   "Pose JSON: {\"pose\": [90 numbers]}, {\"joints\": {\"l_arm\": {\"euler_deg\": [x, y, z]}}}, a list "
                   "of them, or the poses.json this verb writes");
  verb->add_option("--motion", args->motion, "Motion folder from `pixelcloth motion import`: every frame posed");
  verb->add_option("--random", args->random,
                   "Number of random poses from the paper's sampler (half-normal centre line; uniform azimuth, "
                   "sine-altitude and twist for the arms; arms inside the torso rejected), 1 to 10000")
      ->check(CLI::Range(1, 10000));
  verb->add_option("--seed", args->seed, "Seed of the random poses")->capture_default_str();
  verb->add_option("--out", args->out, "Output folder (posed_NNN.obj, poses.json, poses.npy, posed.png)")->required();
  verb->callback([args] { runPose(*args); });
}

}  // namespace pixelcloth::apps
