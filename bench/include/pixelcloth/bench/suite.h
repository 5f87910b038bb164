#pragma once

// The speed goals, measured end to end (`pixelcloth bench`; docs/bench.md): each figure is one JSON object
// {"name", "value", "unit", "goal"}, lower is better unless it says "higher_is_better"; some carry a "bar" (the figure
// it must not miss) and the learned path's the same run's sgemm peak ("peak_gflops"), since speed goals on a shared
// machine are fractions of a peak measured beside them.

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace pixelcloth::bench {

/// The suites: body to simulation and files; the decoders at the paper's width; the PCA filter's fit.
/// The Newton equilibrium solver's T-shirt figures (a few minutes) are a suite of their own, and its probe over unseen
/// poses, meshes, continuation paths, an imported garment and an imported body (tens of minutes) another, not part
/// of "all".
enum class Suite { Procedural, Learn, Stitch, Motion, Equilibrium, EquilibriumProbe };
/// "procedural", "learn", "stitch", "motion", "equilibrium", "equilibrium_probe"
const char* suiteName(Suite suite);
Suite suiteFromName(const std::string& name, const std::string& context);  ///< InputError naming `context` otherwise

/// Receives each figure as soon as it is measured.
using FigureSink = std::function<void(const nlohmann::ordered_json& figure)>;

/// How much each suite measures.
struct SuiteOptions {
  int repeats = 5;        ///< runs per figure, the median reported, [1, 100]
  int epochShirts = 400;  ///< shirts simulated for learn.epoch_seconds_w025 (80% train), [10, 100000]
  int probePoses = 32;    ///< poses the equilibrium probe simulates per mesh, path, garment and body, [2, 10000]
  /// The probe's Coulomb friction of cloth on the body, [0, 2]; < 0: the Newton solver's default (frictionless).
  double probeFriction = -1;
};

/// Measures `suite`, handing each figure to `sink`. Notes on what was measured go to stderr.
void runSuite(Suite suite, const SuiteOptions& options, const FigureSink& sink);

}  // namespace pixelcloth::bench
