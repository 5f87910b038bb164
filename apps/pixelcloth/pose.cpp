// pixelcloth pose: skin a body folder into given or random poses.
#include <cstdio>
#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/body.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/core/pose_io.h"
#include "pixelcloth/core/previews.h"
#include "pixelcloth/core/progress.h"
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
  ensureOutputFolder(args.out);
  std::filesystem::path out(args.out);
  nlohmann::json list = nlohmann::json::array();
  std::vector<float> vectors;
  std::vector<RgbImage> pictures;
  View view;
  view.width = view.height = 320;
  view.azimuthDegrees = 20;
  view.elevationDegrees = 10;
  // The same scale for every pose: the reach of the arms around the body's rest bounding box.
  for (int i = 0; i < body.mesh.numVertices(); ++i) view.bounds.extend(body.mesh.V.row(i).transpose().eval());
  view.bounds.extend(Eigen::Vector3d(view.bounds.center().x(), view.bounds.max().y() + 0.3, 0.6));
  view.bounds.extend(Eigen::Vector3d(view.bounds.center().x(), view.bounds.min().y(), -0.6));
  Progress progress("pose", static_cast<std::int64_t>(poses.size()));
  for (size_t i = 0; i < poses.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "posed_%03zu.obj", i);
    Mesh posed;
    posed.V = body.posedVertices(poses[i]);
    posed.F = body.mesh.F;
    writeMesh(out / name, posed);
    nlohmann::json entry = poseToJson(poses[i]);
    entry["mesh"] = name;
    list.push_back(entry);
    Eigen::VectorXf v = poses[i].toVector();
    vectors.insert(vectors.end(), v.data(), v.data() + v.size());
    if (pictures.size() < 24) pictures.push_back(renderPosedBody(body, poses[i], view));
    progress.advance();
  }
  progress.finish();
  writeNpy(out / "poses.npy", vectors, {static_cast<std::int64_t>(poses.size()), kPoseSize});
  writeJson(out / "poses.json", {{"body", args.body}, {"seed", args.seed}, {"amount", args.amount}, {"poses", list}});
  writePng(out / "posed.png", contactSheet(pictures, 6));
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
