#pragma once

// The paper's experiments on pixelcloth's own data, run end to end (DESIGN.md, "eval/"): simulated T-shirt and necktie
// datasets; Table 1 (the whole-garment CNN by loss); whole garment against 28 patches; Table 2 (fully connected
// networks, direct and through 128 principal components, in three spaces); the PCA filter swept over k and the GAN
// blender; the same shirts rebased onto other body shapes and broken skinning; the necktie; and the learned refinement
// of the marker reconstruction. Every step reuses what an earlier run left in the output folder (datasets and
// trainings resume, finished ones are kept). Results come back typed; viz/ draws them and writes the report.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pixelcloth/data/dataset.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/sim/garment_sim.h"
#include "pixelcloth/stitch/evaluate.h"
#include "pixelcloth/stitch/pca_filter.h"

namespace pixelcloth::eval {

/// The two sizes of the plan: a smoke run of a few minutes, and the full run of about two hours on 2 cores.
enum class Scale { Small, Full };
const char* scaleName(Scale scale);                                        ///< "small", "full"
Scale scaleFromName(const std::string& name, const std::string& context);  ///< InputError naming `context` otherwise

/// A body the shirts are rebased onto (the paper's wrong body shapes and broken skinning).
struct BodyVariant {
  std::string name;            ///< e.g. "shape_-1", "weights_torso"
  double shape = 0;            ///< the mannequin's shape parameter
  std::string corruptWeights;  ///< "", "torso" or "torso+arm" (body::corruptUpperArmWeights)
};

/// How long and how wide one family of CNNs trains.
struct CnnBudget {
  double width = 0.125;  ///< channel multiplier (the paper's is 1)
  int epochs = 3;
  learn::Schedule schedule = learn::Schedule::Constant;  ///< the learning rate over the run
};

/// What the experiments do, and how big.
struct ExperimentPlan {
  int tshirts = 40;   ///< T-shirt samples simulated
  int neckties = 60;  ///< necktie samples simulated
  /// The whole-garment decoder that stands against the patches and the fully connected baselines.
  CnnBudget whole;
  /// The 28 pose-only patch decoders.
  CnnBudget patches;
  /// The 28 residual patch decoders of the learned refinement (their targets are the small marker-fill errors).
  CnnBudget residual;
  /// The comparisons within one architecture: Table 1's three losses and the body-shape and skinning rows (each
  /// against the L1 row of Table 1, trained alike).
  CnnBudget ablation;
  CnnBudget necktie{0.125, 30, learn::Schedule::Constant};
  int fcEpochs = 30;  ///< fully connected baselines' epochs
  int ganEpochs = 1;
  int pcaComponents = 128;          ///< Table 2's principal components (at most the train samples)
  std::vector<BodyVariant> bodies;  ///< the bodies of the shape and skinning experiments
  int threads = 0;                  ///< 0: one per core
  /// The simulator of both datasets: projective dynamics' fixed schedule, or Newton run to static equilibrium.
  sim::SolverKind solver = sim::SolverKind::ProjectiveDynamics;
  /// With the Newton solver, the Coulomb friction of cloth on the body; < 0: the solver's default (frictionless).
  double friction = -1;
  std::uint64_t seed = 1;           ///< the T-shirt dataset's; the necktie's is seed + 1
  double mannequinEdge = 0.0075;    ///< the mannequin's triangle size, metres (tests use coarser bodies)

  /// The plan of `scale`, with the paper's six body shapes (-1 to 2) and both broken skinnings.
  static ExperimentPlan ofScale(Scale scale);
  /// Throws InputError naming the field that is out of range.
  void validate() const;
};

/// The simulator's flags of `plan`'s `pixelcloth generate` and `experiments` commands: "" for projective dynamics,
/// " --solver newton" and " --friction MU" when set.
std::string simulatorFlags(const ExperimentPlan& plan);

/// A dataset the experiments made.
struct DatasetFigures {
  std::filesystem::path folder;
  int samples = 0, train = 0, regularisation = 0, test = 0;
  int accepted = 0;  ///< samples the simulation kept
  int simulated =
      0;  ///< poses simulated (accepted plus rejected by the simulation; the sampler's pruned draws are not)
};

/// A trained model, measured on the train and test splits.
struct ModelFigures {
  std::string name;  ///< its folder under models/, e.g. "whole_l1"
  std::filesystem::path folder;
  double trainCm = std::numeric_limits<double>::quiet_NaN();  ///< mean per-vertex error, cm
  double testCm = std::numeric_limits<double>::quiet_NaN();
  double trainNormal = std::numeric_limits<double>::quiet_NaN();  ///< mean normal cosine distance
  double testNormal = std::numeric_limits<double>::quiet_NaN();
  double seconds = 0;  ///< training wall time of this run (0 when a finished run was kept)
  /// Per stitch mode on the test split (the first is the plain mean); metrics as stitch::evaluate's.
  std::vector<stitch::Evaluation> test;
};

/// Fills `figures`' train and test figures for the model in `figures.folder` on `dataset`: the train split, and the
/// test split (the train split when the dataset has no test split) stitched by each of `modes` (none: the plain mean);
/// `pca` is the filter of pca modes.
void measureModel(ModelFigures& figures, const data::DatasetFolder& dataset,
                  const std::vector<stitch::StitchMode>& modes = {},
                  std::shared_ptr<const stitch::PcaFilter> pca = nullptr);

/// The learned refinement with markers of one noise level (the paper's Sec. 5.2 residual networks).
struct RefinementFigures {
  double noiseCm = 0;
  double markersAloneCm = std::numeric_limits<double>::quiet_NaN();  ///< the marker reconstruction's test error
  ModelFigures residual;                                             ///< residual patches; test[1] is + PCA
};

struct ExperimentResults {
  ExperimentPlan plan;
  std::string scale;  ///< "small", "full" or "custom"
  DatasetFigures tshirt, necktie;
  std::map<std::string, ModelFigures> models;  ///< every trained model by name
  /// The 28 patch decoders' test predictions stitched by the mean, pca:k for k = 1, 2, 4, ... and the rank, and the
  /// GAN.
  std::vector<stitch::Evaluation> stitchSweep;
  int pcaRank = 0;                            ///< the PCA filter's rank (the train split's)
  int pcaK = 0;                               ///< the k the refinement's + PCA rows use: the best of the sweep
  std::vector<RefinementFigures> refinement;  ///< clean markers, then 0.5 cm noise
  std::vector<std::pair<std::string, double>> stepSeconds;
  std::vector<std::string> commands;  ///< the equivalent `pixelcloth` commands, in order
  double seconds = 0;

  /// The model `name`; InputError when the run made none of that name.
  const ModelFigures& model(const std::string& name) const;
};

/// Runs `plan` in `out` (created, or a folder of an earlier run to resume): data/, models/, bodies/, bases/, pca/,
/// each model's test evaluation. Progress on stderr. Throws InputError for a bad plan or a folder holding another
/// run's datasets.
ExperimentResults runExperiments(const ExperimentPlan& plan, const std::filesystem::path& out,
                                 const std::string& scale = "custom");

}  // namespace pixelcloth::eval
