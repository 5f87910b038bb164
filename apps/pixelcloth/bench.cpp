// pixelcloth bench: the speed goals (bench::runSuite), one JSON object per line {"name", "value", "unit", "goal"}.
#include "pixelcloth/bench/suite.h"

#include <iostream>
#include <memory>

#include "verbs.h"

namespace pixelcloth::apps {

void registerBench(CLI::App& app) {
  auto options = std::make_shared<bench::SuiteOptions>();
  CLI::App* verb = app.add_subcommand("bench",
                                      "Measure the speed goals; prints one JSON object per line "
                                      "{name, value, unit, goal} (lower is better)");
  verb->add_option("--repeats", options->repeats, "Runs per figure (the median is reported)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  verb->add_option("--epoch-shirts", options->epochShirts,
                   "Shirts simulated for learn.epoch_seconds_w025, 80% of them trained on (fewer for a quick check)")
      ->capture_default_str()
      ->check(CLI::Range(10, 100000));
  verb->add_option("--probe-poses", options->probePoses,
                   "Poses the equilibrium probe simulates on each mesh, continuation path, garment and body")
      ->capture_default_str()
      ->check(CLI::Range(2, 10000));
  verb->add_option("--probe-friction", options->probeFriction,
                   "Coulomb friction of cloth on the body in the equilibrium probe (default: the Newton solver's, "
                   "frictionless)")
      ->check(CLI::Range(0.0, 2.0));
  auto only = std::make_shared<std::string>("all");
  verb->add_option("--only", *only,
                   "Which figures: all, procedural (body to simulation and files), learn, stitch (the PCA filter), "
                   "motion (a clip to an animated garment), equilibrium (the Newton solver, a few minutes) or "
                   "equilibrium_probe (the Newton solver on unseen poses, four meshes, two continuation paths, an "
                   "imported garment and an imported body: tens of minutes; not part of all)")
      ->capture_default_str()
      ->check(CLI::IsMember({"all", "procedural", "learn", "stitch", "motion", "equilibrium", "equilibrium_probe"}));
  verb->callback([options, only] {
    const bench::FigureSink print = [](const nlohmann::ordered_json& figure) {
      std::cout << figure.dump() << std::endl;
    };
    for (bench::Suite suite : {bench::Suite::Procedural, bench::Suite::Learn, bench::Suite::Stitch,
                               bench::Suite::Motion, bench::Suite::Equilibrium, bench::Suite::EquilibriumProbe})
      if ((*only == "all" && suite != bench::Suite::EquilibriumProbe) || *only == bench::suiteName(suite))
        bench::runSuite(suite, *options, print);
  });
}

}  // namespace pixelcloth::apps
