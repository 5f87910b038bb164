// pixelcloth generate: simulate a dataset of (pose, garment shape) samples, resumable and shardable.
#include "pixelcloth/sim/generate.h"

#include <memory>

#include "pixelcloth/core/log.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct GenerateArgs {
  sim::GenerateOptions options;
  bool quiet = false;
  std::string out;
  std::string solver = "pd";
  double stepDegrees = 0;  ///< 0: the solver's own default
  double friction = -1;    ///< < 0: the solver's own default (the Newton path is frictionless)
};

void runGenerate(GenerateArgs args) {
  if (args.quiet) core::setLogLevel(core::LogLevel::Warning);
  sim::SimulationOptions& simulation = args.options.simulation;
  simulation.kind = sim::parseSolverKind(args.solver, "generate --solver");
  if (args.stepDegrees > 0)
    (simulation.kind == sim::SolverKind::Newton ? simulation.newton.stepDegrees : simulation.stepDegrees) =
        args.stepDegrees;
  if (args.friction >= 0) {
    if (simulation.kind != sim::SolverKind::Newton)
      throw core::InputError(
          "generate --friction: friction is a setting of --solver newton (projective dynamics has "
          "its own contact friction), got --solver " +
          args.solver);
    simulation.newton.solver.friction = args.friction;
  }
  const sim::GenerateReport report = sim::generateDataset(args.out, args.options);
  PIXELCLOTH_INFO("generate: " << report.added << " samples simulated (" << report.resumed << " already done, "
                               << report.rejected << " simulations rejected) in " << report.seconds << " s -> "
                               << args.out << "/{manifest.json, poses.npy, positions.npy, offsets.npy, split.npy}");
}
}  // namespace

void registerGenerate(CLI::App& app) {
  auto args = std::make_shared<GenerateArgs>();
  sim::GenerateOptions& o = args->options;
  CLI::App* verb = app.add_subcommand(
      "generate", "Simulate a dataset: random poses (the paper's sampler), quasistatic drape, offsets; resumable");
  verb->add_option("--count", o.count, "Samples in the whole dataset (all shards), 1 to 10000000")->required();
  verb->add_option("--seed", o.seed, "Seed of poses and splits")->capture_default_str();
  verb->add_option("--out", args->out, "Dataset folder (created, or resumed when it holds a partial run)")->required();
  verb->add_option("--garment", o.garment, kGarmentHelp)->capture_default_str();
  verb->add_option("--shard", o.shard, "K/N: make only the K-th of N contiguous slices (merge with 'dataset merge')")
      ->capture_default_str();
  verb->add_option("--body", o.bodyFolder, "Body folder from 'pixelcloth body' (default: the built-in mannequin)");
  verb->add_option("--body-shape", o.bodyShape, "Mannequin girth in [-1, 2] (thinner .. thicker)")
      ->capture_default_str();
  verb->add_option("--corrupt-weights", o.corruptWeights,
                   "Skinning artifacts: move upper-arm weight to the torso ('torso') or torso and forearm "
                   "('torso+arm')");
  verb->add_option("--corrupt-fraction", o.corruptFraction, "Fraction of upper-arm weight moved")
      ->capture_default_str();
  verb->add_option("--solver", args->solver,
                   "Quasistatic solver: 'pd' (projective dynamics, fixed schedule) or 'newton' (run to static "
                   "equilibrium, verified by the net force on every vertex; about 40x slower)")
      ->capture_default_str();
  verb->add_option("--step-degrees", args->stepDegrees,
                   "Continuation: the body moves from the rest pose to each sampled pose in steps of at most this "
                   "many degrees of any joint's rotation, the cloth solved at each (default: 25 with pd, 10 with "
                   "newton)")
      ->check(CLI::Range(1.0, 180.0));
  verb->add_option("--friction", args->friction,
                   "With --solver newton: Coulomb friction coefficient of cloth on the body (default 0, "
                   "frictionless). Lagged per continuation step; a pose whose friction does not come within the "
                   "Coulomb bound is rejected as not_converged")
      ->check(CLI::Range(0.0, 2.0));
  verb->add_option("--threads", o.threads, "Worker threads (0: one per core)")->capture_default_str();
  verb->add_flag("--quiet", args->quiet, "No progress on stderr");
  verb->callback([args] { runGenerate(*args); });
}

}  // namespace pixelcloth::apps
