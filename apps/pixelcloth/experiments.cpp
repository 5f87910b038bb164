// pixelcloth experiments: the paper's experiments on pixelcloth's own data, end to end, with results.md.
#include "pixelcloth/eval/experiments.h"

#include <iostream>
#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/viz/experiments_report.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct ExperimentsArgs {
  std::string scale = "small", out, solver = "pd";
  double friction = -1;  ///< < 0: the solver's default
  int threads = 0;
};

void runExperiments(const ExperimentsArgs& args) {
  const eval::Scale scale = eval::scaleFromName(args.scale, "experiments --scale");
  eval::ExperimentPlan plan = eval::ExperimentPlan::ofScale(scale);
  plan.threads = args.threads;
  plan.solver = sim::parseSolverKind(args.solver, "experiments --solver");
  plan.friction = args.friction;
  const std::filesystem::path out =
      args.out.empty() ? std::filesystem::path("experiments") / args.scale : std::filesystem::path(args.out);
  core::checkOutputFolder(out);
  core::checkRunFolder(out, {"", {}, "an experiments run"});
  const eval::ExperimentResults results = eval::runExperiments(plan, out, args.scale);
  viz::writeExperimentReport(results, out);
  std::cout << "experiments: " << (out / "results.md").string() << " (" << static_cast<int>(results.seconds) << " s)\n";
}
}  // namespace

void registerExperiments(CLI::App& app) {
  auto args = std::make_shared<ExperimentsArgs>();
  CLI::App* verb = app.add_subcommand(
      "experiments",
      "The paper's experiments on simulated T-shirts and neckties: its tables with its figures beside ours, the PCA "
      "filter and GAN, body shapes and broken skinning, the necktie, and the learned refinement of marker "
      "reconstructions (results.md and figures/ in --out). A run resumes what an earlier one left in --out");
  verb->add_option("--scale", args->scale,
                   "small (a smoke run of a few minutes) or full (about two hours on 2 cores)")
      ->capture_default_str()
      ->check(CLI::IsMember({"small", "full"}));
  verb->add_option("--out", args->out, "Output folder (default: experiments/SCALE)");
  verb->add_option("--solver", args->solver,
                   "The datasets' simulator: 'pd' (projective dynamics, fixed schedule) or 'newton' (run to static "
                   "equilibrium; about 8 s a T-shirt pose on one core)")
      ->capture_default_str()
      ->check(CLI::IsMember({"pd", "newton"}));
  verb->add_option("--friction", args->friction,
                   "With --solver newton: Coulomb friction of cloth on the body (default 0, frictionless)")
      ->check(CLI::Range(0.0, 2.0));
  verb->add_option("--threads", args->threads, "Worker threads (0: one per core)")
      ->capture_default_str()
      ->check(CLI::Range(0, 256));
  verb->callback([args] { runExperiments(*args); });
}

}  // namespace pixelcloth::apps
