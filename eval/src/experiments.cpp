#include "pixelcloth/eval/experiments.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>
#include <thread>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/learn/prediction_inputs.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/recon/base.h"
#include "pixelcloth/sim/generate.h"
#include "pixelcloth/stitch/gan.h"
#include "pixelcloth/stitch/pca_filter.h"
#include "pixelcloth/stitch/stitcher.h"

namespace pixelcloth::eval {

namespace fs = std::filesystem;

namespace {
const core::EnumNames<Scale, 2> kScales{"scale", {{{Scale::Small, "small"}, {Scale::Full, "full"}}}};

using Clock = std::chrono::steady_clock;

/// The run's state: the plan, the output folder, the results so far and the step clock.
class Run {
 public:
  Run(const ExperimentPlan& plan, fs::path out, std::string scale) : out_(std::move(out)) {
    results_.plan = plan;
    results_.scale = std::move(scale);
    threads_ = plan.threads > 0 ? plan.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  }

  ExperimentResults& results() { return results_; }
  const fs::path& out() const { return out_; }
  int threads() const { return threads_; }

  /// Ends a step: its wall time since the last one.
  void step(const std::string& name) {
    results_.stepSeconds.emplace_back(name, core::secondsSince(stepStart_));
    PIXELCLOTH_INFO("experiments: " << name << " done");
    stepStart_ = Clock::now();
  }

  void command(const std::string& text) { results_.commands.push_back(text); }

  /// A simulated dataset of `count` samples of `garment` in data/`name` (resumed when an earlier run left it).
  DatasetFigures dataset(const std::string& name, const std::string& garment, int count, std::uint64_t seed) {
    sim::GenerateOptions options;
    options.garment = garment;
    options.count = count;
    options.seed = seed;
    options.threads = threads_;
    options.mannequinEdge = results_.plan.mannequinEdge;
    options.simulation.kind = results_.plan.solver;
    if (results_.plan.friction >= 0) options.simulation.newton.solver.friction = results_.plan.friction;
    const fs::path folder = out_ / "data" / name;
    // A finished dataset of this garment, size, seed, solver and friction is kept as it is; anything else is
    // generated, resumed or refused by sim::generateDataset (which rebuilds the body and dressing to check them
    // against the folder's).
    const nlohmann::json simulator = sim::simulationSettings(options.simulation);
    std::error_code ec;
    const bool finished = fs::is_regular_file(folder / "manifest.json", ec) && [&] {
      const data::DatasetSettings s = data::readDatasetInfo(folder).settings;
      return s.garment == garment && s.count == count && s.seed == seed && s.rows() == count &&
             s.generator.value("solver", "") == simulator["solver"] &&
             s.generator.value("friction", -1.0) == simulator["friction"].get<double>();
    }();
    if (!finished) sim::generateDataset(folder, options);
    const std::string solver = simulatorFlags(results_.plan);
    command("pixelcloth generate --count " + std::to_string(count) + " --seed " + std::to_string(seed) + " --garment " +
            garment + solver + " --out data/" + name);
    return figuresOf(folder);
  }

  static DatasetFigures figuresOf(const fs::path& folder) {
    const data::DatasetInfo info = data::readDatasetInfo(folder);
    DatasetFigures figures;
    figures.folder = folder;
    figures.samples = info.counts.total();
    figures.train = info.counts.train;
    figures.regularisation = info.counts.regularisation;
    figures.test = info.counts.test;
    figures.accepted = info.stats.accepted;
    figures.simulated = info.stats.simulated();
    return figures;
  }

  /// Trains models/`name` on `dataset` (resuming, or keeping a finished run) and measures it on the train split and,
  /// by each of `modes` (none: the plain mean), the test split. `pca`: the filter of pca modes.
  const ModelFigures& model(const std::string& name, const fs::path& dataset, const learn::TrainOptions& options,
                            const std::string& flags, const std::vector<stitch::StitchMode>& modes = {},
                            std::shared_ptr<const stitch::PcaFilter> pca = nullptr) {
    ModelFigures figures;
    figures.name = name;
    figures.folder = out_ / "models" / name;
    learn::TrainOptions threaded = options;
    threaded.threads = threads_;
    const learn::TrainReport report = learn::train(dataset, figures.folder, threaded);
    const bool trainedHere = std::any_of(report.networks.begin(), report.networks.end(),
                                         [&](const auto& n) { return n.resumedAt < options.epochs; });
    figures.seconds = trainedHere ? report.seconds : 0;
    command("pixelcloth train --dataset " + fs::relative(dataset, out_).string() + " " + flags + " --out models/" +
            name);
    measureModel(figures, dataset, modes, std::move(pca));
    return results_.models[name] = std::move(figures);
  }

 private:
  fs::path out_;
  ExperimentResults results_;
  int threads_ = 1;
  Clock::time_point stepStart_ = Clock::now();
};

learn::TrainOptions cnnOptions(const CnnBudget& budget, learn::Architecture architecture) {
  learn::TrainOptions options;
  options.model.architecture = architecture;
  options.model.width = budget.width;
  options.epochs = budget.epochs;
  options.schedule = budget.schedule;
  options.seed = 0;
  return options;
}

/// The `pixelcloth train` flags of `budget`.
std::string cnnFlags(const CnnBudget& budget) {
  std::ostringstream flags;
  flags << "--width " << budget.width << " --epochs " << budget.epochs;
  if (budget.schedule != learn::Schedule::Constant) flags << " --schedule " << learn::scheduleName(budget.schedule);
  flags << " --seed 0";
  return flags.str();
}

void validateBudget(const CnnBudget& budget, const char* name) {
  PIXELCLOTH_CHECK(std::isfinite(budget.width) && budget.width > 0 && budget.width <= 4,
                   "experiments: " << name << " width " << budget.width << ", expected (0, 4]");
  PIXELCLOTH_CHECK(budget.epochs >= 1,
                   "experiments: " << name << " epochs " << budget.epochs << ", expected 1 or more");
}

}  // namespace

void measureModel(ModelFigures& figures, const data::DatasetFolder& dataset,
                  const std::vector<stitch::StitchMode>& modes, std::shared_ptr<const stitch::PcaFilter> pca) {
  const learn::PredictionInputs inputs =
      learn::datasetPredictionInputs(figures.folder, dataset, {}, learn::Engine::OneDnn);
  const stitch::Evaluation train = stitch::evaluate(*inputs.model, inputs.data, data::Split::Train).front();
  figures.trainCm = train.metrics["vertex_error_cm"].get<double>();
  figures.trainNormal = train.metrics["normal_cosine_distance"].get<double>();
  std::vector<stitch::Stitcher> stitchers;
  for (const stitch::StitchMode& mode : modes) stitchers.emplace_back(inputs.data.garment, mode, pca);
  std::vector<const stitch::Stitcher*> pointers;
  for (const stitch::Stitcher& s : stitchers) pointers.push_back(&s);
  const data::Split test = inputs.data.test.empty() ? data::Split::Train : data::Split::Test;
  figures.test = stitch::evaluate(*inputs.model, inputs.data, test, pointers);
  figures.testCm = figures.test.front().metrics["vertex_error_cm"].get<double>();
  figures.testNormal = figures.test.front().metrics["normal_cosine_distance"].get<double>();
}

const char* scaleName(Scale scale) { return kScales.name(scale); }

Scale scaleFromName(const std::string& name, const std::string& context) { return kScales.fromName(name, context); }

std::string simulatorFlags(const ExperimentPlan& plan) {
  if (plan.solver == sim::SolverKind::ProjectiveDynamics) return "";
  std::ostringstream flags;
  flags << " --solver " << sim::solverKindName(plan.solver);
  if (plan.friction >= 0) flags << " --friction " << plan.friction;
  return flags.str();
}

ExperimentPlan ExperimentPlan::ofScale(Scale scale) {
  ExperimentPlan plan;
  if (scale == Scale::Full) {
    // 400 T-shirts (320 train) and networks wide enough to fit them: the paper's width for the whole decoder and half
    // of it for the 28 patch decoders, each with a cosine schedule (docs/learning.md, "Width and the learning-rate
    // schedule"). The comparisons within one architecture (losses, bodies) and the residual decoders, whose targets
    // are small, train at a quarter width. About two hours on 2 cores.
    plan.tshirts = 400;
    plan.neckties = 1700;
    plan.whole = {1.0, 50, learn::Schedule::Cosine};
    plan.patches = {0.5, 20, learn::Schedule::Cosine};
    plan.residual = {0.25, 10, learn::Schedule::Cosine};
    plan.ablation = {0.25, 10, learn::Schedule::Cosine};
    plan.necktie = {0.125, 50, learn::Schedule::Cosine};
    plan.fcEpochs = 40;
    plan.ganEpochs = 3;
  }
  for (double shape : {-1.0, -0.5, 0.5, 1.0, 1.5, 2.0}) {
    std::ostringstream name;
    name << "shape_" << shape;
    plan.bodies.push_back({name.str(), shape, ""});
  }
  plan.bodies.push_back({"weights_torso", 0, "torso"});
  plan.bodies.push_back({"weights_torso+arm", 0, "torso+arm"});
  return plan;
}

void ExperimentPlan::validate() const {
  PIXELCLOTH_CHECK(tshirts >= 4 && neckties >= 4,
                   "experiments: " << tshirts << " T-shirts and " << neckties << " neckties, expected 4 or more each");
  validateBudget(whole, "whole decoder");
  validateBudget(patches, "patch decoders");
  validateBudget(residual, "residual decoders");
  validateBudget(ablation, "ablation");
  validateBudget(necktie, "necktie");
  PIXELCLOTH_CHECK(fcEpochs >= 1 && ganEpochs >= 1, "experiments: fully connected epochs "
                                                        << fcEpochs << ", GAN epochs " << ganEpochs
                                                        << ", expected 1 or more");
  PIXELCLOTH_CHECK(pcaComponents >= 1, "experiments: " << pcaComponents << " principal components, expected 1 or more");
  PIXELCLOTH_CHECK(threads >= 0 && threads <= 256, "experiments: threads " << threads << ", expected 0 to 256");
  PIXELCLOTH_CHECK(friction < 0 || (solver == sim::SolverKind::Newton && friction <= 2),
                   "experiments: friction " << friction << " with the " << sim::solverKindName(solver)
                                            << " solver, expected 0 to 2 with newton (projective dynamics has its "
                                               "own contact friction)");
  for (const BodyVariant& body : bodies) {
    PIXELCLOTH_CHECK(!body.name.empty() && body.name.find('/') == std::string::npos,
                     "experiments: body variant name '" << body.name << "', expected a plain folder name");
    PIXELCLOTH_CHECK(
        body.corruptWeights.empty() || body.corruptWeights == "torso" || body.corruptWeights == "torso+arm",
        "experiments: body " << body.name << ": corrupt weights '" << body.corruptWeights
                             << "', expected torso or torso+arm");
    body::MannequinOptions{body.shape, mannequinEdge}.validate();
  }
}

const ModelFigures& ExperimentResults::model(const std::string& name) const {
  const auto found = models.find(name);
  PIXELCLOTH_CHECK(found != models.end(), "experiments: no model '" << name << "' in these results");
  return found->second;
}

ExperimentResults runExperiments(const ExperimentPlan& plan, const fs::path& out, const std::string& scale) {
  plan.validate();
  fs::create_directories(out);
  const auto start = Clock::now();
  Run run(plan, out, scale);
  ExperimentResults& results = run.results();

  // Data.
  results.tshirt = run.dataset("tshirt", "tshirt", plan.tshirts, plan.seed);
  results.necktie = run.dataset("necktie", "necktie", plan.neckties, plan.seed + 1);
  const fs::path shirts = results.tshirt.folder;
  run.step("datasets");

  // Table 1: the whole-garment CNN by loss (no normal loss, then L2 with the paper's 0.01).
  const std::string ablation = cnnFlags(plan.ablation);
  for (const auto& [name, loss, normal] :
       {std::tuple<const char*, learn::ImageLoss, double>{"whole_l1", learn::ImageLoss::L1, 0.0},
        {"whole_l2", learn::ImageLoss::L2, 0.0},
        {"whole_l2n", learn::ImageLoss::L2, 0.01}}) {
    learn::TrainOptions options = cnnOptions(plan.ablation, learn::Architecture::Whole);
    options.loss = loss;
    options.normalWeight = normal;
    std::ostringstream flags;
    flags << "--model whole --loss " << learn::imageLossName(loss) << " --normal-weight " << normal << " " << ablation;
    run.model(name, shirts, options, flags.str());
  }
  run.step("Table 1 (loss)");

  // Whole garment against 28 patches, both with the garment's default normal weight.
  run.model("patch_l1", shirts, cnnOptions(plan.patches, learn::Architecture::Patch),
            "--model patch --loss l1 " + cnnFlags(plan.patches));
  run.model("whole_default", shirts, cnnOptions(plan.whole, learn::Architecture::Whole),
            "--model whole --loss l1 " + cnnFlags(plan.whole));
  run.step("whole against patches");

  // Table 2: fully connected, direct and through principal components, in the three spaces.
  const int components = std::min(plan.pcaComponents, results.tshirt.train);
  for (const learn::OffsetSpace space :
       {learn::OffsetSpace::Local, learn::OffsetSpace::Root, learn::OffsetSpace::Positions}) {
    for (const learn::Architecture architecture :
         {learn::Architecture::FullyConnected, learn::Architecture::FullyConnectedPca}) {
      learn::TrainOptions options;
      options.model.architecture = architecture;
      options.model.pcaComponents = components;
      options.space = space;
      options.epochs = plan.fcEpochs;
      const bool pca = architecture == learn::Architecture::FullyConnectedPca;
      const std::string name = std::string(pca ? "fcpca_" : "fc_") + learn::offsetSpaceName(space);
      run.model(name, shirts, options,
                std::string("--model ") + learn::architectureName(architecture) +
                    (pca ? " --components " + std::to_string(components) : "") + " --space " +
                    learn::offsetSpaceName(space) + " --epochs " + std::to_string(plan.fcEpochs) + " --seed 0");
    }
  }
  run.step("Table 2 (fully connected)");

  // The PCA filter swept over k, and the GAN blender, on the patch decoders' test predictions. The k the refinement
  // uses is chosen on the regularisation split (the train split when a small dataset has none).
  const learn::TrainingData localData = learn::loadTrainingData(shirts, learn::OffsetSpace::Local, {});
  // The filter lives in pca/ of the output folder: fitted on the train split on the first run, reused after.
  auto pca = std::make_shared<const stitch::PcaFilter>(stitch::loadOrFitPcaFilter(localData, out));
  results.pcaRank = pca->rank();
  run.command("pixelcloth pca --dataset data/tshirt --out pca");
  stitch::GanOptions gan;
  gan.epochs = plan.ganEpochs;
  gan.threads = run.threads();
  const ModelFigures& patches = results.model("patch_l1");
  {
    const learn::PredictionInputs inputs =
        learn::datasetPredictionInputs(patches.folder, shirts, {}, learn::Engine::OneDnn);
    const fs::path ganFolder = out / "models" / "gan";
    if (!fs::is_regular_file(ganFolder / "model.tensors")) stitch::trainGan(*inputs.model, inputs.data, gan, ganFolder);
    run.command("pixelcloth train --model gan --patch-model models/patch_l1 --dataset data/tshirt --epochs " +
                std::to_string(plan.ganEpochs) + " --out models/gan");
    std::vector<stitch::StitchMode> modes = stitch::pcaSweepModes(results.pcaRank);
    modes.push_back({stitch::StitchKind::Gan, 0, ganFolder});
    std::vector<stitch::Stitcher> stitchers;
    for (const stitch::StitchMode& mode : modes) stitchers.emplace_back(inputs.data.garment, mode, pca);
    std::vector<const stitch::Stitcher*> pointers;
    for (const stitch::Stitcher& s : stitchers) pointers.push_back(&s);
    results.stitchSweep = stitch::evaluate(*inputs.model, inputs.data, data::Split::Test, pointers);
    pointers.pop_back();  // k is chosen among the pca modes
    const data::Split chooseOn = inputs.data.regularisation.empty() ? data::Split::Train : data::Split::Regularisation;
    const std::vector<stitch::Evaluation> chosen = stitch::evaluate(*inputs.model, inputs.data, chooseOn, pointers);
    results.pcaK = chosen[stitch::bestPcaMode(chosen)].mode.components;
    run.command(
        "pixelcloth evaluate --model models/patch_l1 --dataset data/tshirt --split test --pca pca --stitch "
        "mean,pca:1,...,gan:models/gan --out eval/stitch_sweep");
  }
  run.step("PCA filter and GAN");

  // Wrong body shapes and broken skinning: the same shirts rebased onto each body, the whole CNN trained on each as
  // Table 1's L1 row was on the body simulated on.
  for (const BodyVariant& variant : plan.bodies) {
    const fs::path rebased = out / "data" / ("tshirt_" + variant.name);
    if (!fs::is_regular_file(rebased / "manifest.json")) {
      body::MannequinOptions mannequin;
      mannequin.shape = variant.shape;
      mannequin.edgeLength = plan.mannequinEdge;
      body::Body body = body::makeMannequin(mannequin);
      nlohmann::json description = {{"kind", "mannequin"}, {"shape", variant.shape}};
      if (!variant.corruptWeights.empty()) {
        body.weights = body::corruptUpperArmWeights(body.skeleton, body.weights, variant.corruptWeights, 0.5);
        body.parts = body::collisionParts(body);
        description["corrupt_weights"] = variant.corruptWeights;
      }
      data::rebaseDataset(shirts, body, description, rebased);
    }
    run.command("pixelcloth body " +
                (variant.corruptWeights.empty() ? "--shape " + std::to_string(variant.shape)
                                                : "--corrupt-weights " + variant.corruptWeights) +
                " --out bodies/" + variant.name + " && pixelcloth dataset rebase data/tshirt --body bodies/" +
                variant.name + " --out data/tshirt_" + variant.name);
    learn::TrainOptions options = cnnOptions(plan.ablation, learn::Architecture::Whole);
    options.normalWeight = 0;
    run.model("whole_" + variant.name, rebased, options, "--model whole --loss l1 --normal-weight 0 " + ablation);
  }
  run.step("body shapes and skinning");

  // The necktie: 36 pose floats, root-frame offsets and the edge loss (the garment's defaults).
  learn::TrainOptions tie = cnnOptions(plan.necktie, learn::Architecture::Necktie);
  tie.batch = 4;
  run.model("necktie", results.necktie.folder, tie, "--model necktie --batch 4 " + cnnFlags(plan.necktie));
  run.step("necktie");

  // The learned refinement of the marker reconstruction: residual patch decoders on clean and noisy markers.
  for (const auto& [name, noiseCm] : {std::pair<const char*, double>{"clean", 0.0}, {"noisy", 0.5}}) {
    const fs::path bases = out / "bases" / name;
    if (!fs::is_regular_file(bases / "manifest.json")) {
      recon::BaseSetOptions options;
      options.capture.noise = noiseCm / 100;
      options.threads = run.threads();
      recon::writeDatasetBases(shirts, bases, options);
    }
    std::ostringstream noise;
    noise << noiseCm;
    run.command("pixelcloth reconstruct --dataset data/tshirt --write-base bases/" + std::string(name) + " --noise " +
                noise.str());
    learn::TrainOptions options = cnnOptions(plan.residual, learn::Architecture::Patch);
    options.residual = bases;
    RefinementFigures refinement;
    refinement.noiseCm = noiseCm;
    refinement.residual =
        run.model(std::string("residual_") + name, shirts, options,
                  "--model patch --residual bases/" + std::string(name) + " " + cnnFlags(plan.residual),
                  {stitch::StitchMode{}, {stitch::StitchKind::Pca, results.pcaK, {}}}, pca);
    const nlohmann::json& base = refinement.residual.test.front().metrics["base_vertex_error_cm"];
    if (base.is_number()) refinement.markersAloneCm = base.get<double>();
    results.refinement.push_back(std::move(refinement));
  }
  run.step("learned refinement");
  results.seconds = core::secondsSince(start);
  return std::move(results);
}

}  // namespace pixelcloth::eval
