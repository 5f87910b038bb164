// pixelcloth pose: skin a body folder into given or random poses.
#include <memory>

#include "pixelcloth/core/body.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/pose_io.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct PoseArgs {
  std::string body;
  std::string pose;
  int random = 0;
  std::uint64_t seed = 0;
  double amount = 0.6;
  std::string out;
};

void runPose(const PoseArgs& args) {
  using namespace pixelcloth::core;
  PIXELCLOTH_CHECK(args.pose.empty() != (args.random == 0),
                   "pose: give either --pose POSE.json or --random N (with --seed S)");
  PIXELCLOTH_CHECK(args.random >= 0 && args.random <= 10000,
                   "pose: --random must be in [1, 10000], got " << args.random);
  Body body = loadBody(args.body);
  std::vector<Pose> poses;
  if (!args.pose.empty()) {
    poses.push_back(readPose(args.pose));
  } else {
    for (int i = 0; i < args.random; ++i) poses.push_back(randomPose(args.seed * 1000003ull + i, args.amount));
  }
  writePosedBodies(args.out, body, poses, {{"body", args.body}, {"seed", args.seed}, {"amount", args.amount}});
  PIXELCLOTH_INFO("pose: " << poses.size() << " posed meshes -> " << args.out
                           << "/{posed_NNN.obj, poses.json, poses.npy, posed.png}");
}
}  // namespace

void registerPose(CLI::App& app) {
  auto args = std::make_shared<PoseArgs>();
  CLI::App* verb = app.add_subcommand("pose", "Pose a body folder by linear blend skinning: posed OBJs and a picture");
  verb->add_option("--body", args->body, "Body folder written by 'pixelcloth body'")->required();
  verb->add_option("--pose", args->pose,
                   "Pose JSON: {\"pose\": [90 numbers]} or {\"joints\": {\"l_arm\": {\"euler_deg\": [x, y, z]}}}");
  verb->add_option("--random", args->random, "Number of random poses (uniform within the joint limits)");
  verb->add_option("--seed", args->seed, "Seed of the random poses")->capture_default_str();
  verb->add_option("--amount", args->amount, "Fraction of each joint range the random poses use (0 = rest, 1 = full)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  verb->add_option("--out", args->out, "Output folder (posed_NNN.obj, poses.json, poses.npy, posed.png)")->required();
  verb->callback([args] { runPose(*args); });
}

}  // namespace pixelcloth::apps
