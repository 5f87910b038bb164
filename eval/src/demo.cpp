#include "pixelcloth/eval/demo.h"

#include <algorithm>
#include <memory>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/learn/predict.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/sim/generate.h"
#include "pixelcloth/sim/pose_sampler.h"
#include "pixelcloth/stitch/evaluate.h"
#include "pixelcloth/stitch/pca_filter.h"
#include "pixelcloth/stitch/stitcher.h"

namespace pixelcloth::eval {

namespace fs = std::filesystem;

namespace {

/// The demo's small CNNs: a few minutes of training on a few dozen samples on two cores. They keep the plain width
/// multiplier (no channel floor, docs/learning.md): on the demo's 32 shirts and 64 Adam steps the floored whole decoder
/// ended further off (4.0 cm against 3.4) in three times the time, and the floored patch decoders, whose 28 crops hold
/// 5.5 times the whole image's pixels, trained four times slower.
learn::TrainOptions smallCnn(learn::Architecture architecture, int epochs) {
  learn::TrainOptions options;
  options.model.architecture = architecture;
  options.model.width = 0.125;
  options.model.minChannels = 0;
  options.epochs = epochs;
  options.batch = 4;
  options.learningRate = 2e-3;
  return options;
}

/// The split a small dataset is measured on: its test split, or its train split when it has none.
data::Split measuredSplit(const learn::TrainingData& data) {
  return data.test.empty() ? data::Split::Train : data::Split::Test;
}

/// The first (at most) two rows of `split`.
std::vector<int> firstRows(const learn::TrainingData& data, data::Split split) {
  const std::vector<int>& rows = data.split(split);
  return {rows.begin(), rows.begin() + std::min<size_t>(2, rows.size())};
}

/// Trains `options` into `folder` (emptied first) on `dataset` and measures it on `measuredSplit`, predicting `shown`.
DemoModel trainAndMeasure(DemoModel model, const fs::path& dataset, const fs::path& baseFolder,
                          const std::vector<int>& shown) {
  fs::remove_all(model.folder);
  model.trained = learn::train(dataset, model.folder, model.options);
  const learn::TrainedModel trained(model.folder, data::datasetGarment(data::readDatasetInfo(dataset)));
  const learn::TrainingData data = learn::loadTrainingData(dataset, trained.space(), baseFolder);
  model.split = measuredSplit(data);
  model.evaluation = stitch::evaluate(trained, data, model.split).front();
  model.shown = stitch::predictRows(trained, data, shown);
  // As pixelcloth evaluate writes it, for the viewer: learning/<model>/ beside the model folder, paths relative to it.
  const fs::path root = model.folder.parent_path(), out = root / "learning" / model.folder.filename();
  nlohmann::json metrics = model.evaluation.metrics;
  metrics["model"] = model.folder.filename().string();
  metrics["dataset"] = fs::relative(dataset, root).string();
  core::ensureOutputFolder(out);
  stitch::writePredictions(out, model.evaluation, data, metrics);
  core::writeJson(out / "metrics.json", metrics);
  return model;
}

}  // namespace

std::vector<DressedGarment> dressTemplates(const body::Body& body) {
  std::vector<DressedGarment> out;
  for (const garment::Garment& garment : {garment::makeTShirt(), garment::makeNecktie()})
    out.push_back({garment, cage::dressGarment(body, cage::bodyCage(body), garment, cage::garmentCage(garment))});
  return out;
}

SimulatedDataset simulateDataset(const fs::path& folder, const fs::path& bodyFolder, const std::string& garment,
                                 int count, std::uint64_t seed, sim::SolverKind solver) {
  fs::remove_all(folder);
  sim::GenerateOptions generate;
  generate.garment = garment;
  generate.count = count;
  generate.seed = seed;
  generate.bodyFolder = bodyFolder;
  generate.simulation.kind = solver;
  SimulatedDataset out;
  out.folder = folder;
  out.seconds = sim::generateDataset(folder, generate).seconds;
  out.check = data::checkDataset(folder);
  out.info = data::readDatasetInfo(folder);
  return out;
}

EquilibriumDemo runEquilibriumDemo(const fs::path& folder, const fs::path& bodyFolder, const fs::path& projective,
                                   const DemoPlan& plan) {
  EquilibriumDemo out;
  out.projective = projective;
  // Both datasets draw sample i's pose from (seed, i, attempt): the poses that neither solver rejected are the same.
  out.newton =
      simulateDataset(folder, bodyFolder, "tshirt", plan.equilibriumSamples, plan.seed, sim::SolverKind::Newton);
  out.comparison = sim::compareDatasets(data::openDataset(projective), data::openDataset(folder));
  return out;
}

PoseFiltering filterSampledPoses(const body::Body& body, int count, std::uint64_t seed) {
  sim::PoseSamplerOptions options;
  options.seed = seed;
  sim::PoseSampler sampler(body, options);
  PoseFiltering out;
  for (int k = 0; k < count; ++k) out.drawn.push_back(sampler.draw());
  for (const body::Pose& pose : out.drawn) {
    if (sampler.armInsideTorso(pose))
      out.tally.reject(data::Rejection::ArmInsideTorso);
    else
      out.simulated.push_back(pose);
  }
  const garment::Garment shirt = garment::makeTShirt();
  const cage::Dressing dressing = cage::dressGarment(body, cage::bodyCage(body), shirt, cage::garmentCage(shirt));
  const std::vector<data::SampleStats> stats = sim::simulatePoses(body, shirt, dressing, out.simulated);
  for (size_t k = 0; k < stats.size(); ++k) {
    out.seconds += stats[k].seconds;
    if (stats[k].rejection == data::Rejection::None) {
      out.kept.push_back(out.simulated[k]);
      out.tally.add(stats[k]);
    } else {
      out.tally.reject(stats[k].rejection);
    }
  }
  return out;
}

DemoReconstruction reconstructDemoDataset(const fs::path& dataset, const fs::path& out) {
  // The spline's length model is fitted on the train split; the test split is rebuilt (every sample when the dataset
  // is too small to have one).
  const data::Dataset opened = data::openDataset(dataset);
  recon::DatasetReconstructionOptions options;
  if (opened.rowsOf(data::Split::Test).empty()) options.split.reset();
  options.meshes = 2;
  fs::remove_all(out);
  DemoReconstruction result;
  result.report = recon::reconstructDataset(dataset, out, options);
  for (int r = 0; r < opened.rows() && result.shown.size() < 2; ++r)
    if (!options.split || opened.split[r] == static_cast<std::uint8_t>(data::Split::Test)) result.shown.push_back(r);
  return result;
}

learn::TrainReport trainNecktie(const fs::path& dataset, const fs::path& out, const DemoPlan& plan) {
  learn::TrainOptions options;
  options.model.architecture = learn::Architecture::Necktie;
  options.model.width = 0.25;
  options.epochs = plan.necktieEpochs;
  options.batch = 2;
  options.learningRate = 2e-3;
  fs::remove_all(out);
  return learn::train(dataset, out, options);
}

DemoLearning runDemoLearning(const fs::path& report, const DemoPlan& plan) {
  const fs::path dataset = report / "dataset_tshirt", baseFolder = report / "bases_tshirt";
  DemoLearning out;
  PIXELCLOTH_INFO("demo: the marker reconstruction of every T-shirt sample, as the residual models' base");
  fs::remove_all(baseFolder);
  out.bases = recon::writeDatasetBases(dataset, baseFolder, {});
  out.data = learn::loadTrainingData(dataset, learn::OffsetSpace::Local, {});
  out.shown = firstRows(out.data, measuredSplit(out.data));

  struct Entry {
    const char* name;
    const char* label;
    learn::Architecture architecture;
    bool residual;
  };
  for (const Entry& e :
       {Entry{"whole", "whole garment, pose in", learn::Architecture::Whole, false},
        Entry{"patch", "28 patches, pose in", learn::Architecture::Patch, false},
        Entry{"residual_patch", "28 patches, residual on the markers' garment", learn::Architecture::Patch, true}}) {
    PIXELCLOTH_INFO("demo: training the " << e.label << " decoder(s)");
    DemoModel model;
    model.name = e.name;
    model.label = e.label;
    model.folder = report / ("model_" + model.name);
    model.options = smallCnn(e.architecture, plan.learningEpochs);
    if (e.residual) {
      model.options.residual = baseFolder;
      model.options.model.inputSize = body::kPoseSize + 3 * out.bases.markers;
    }
    out.models.push_back(trainAndMeasure(std::move(model), dataset, e.residual ? baseFolder : fs::path(), out.shown));
  }
  out.markersAloneCm = out.models.back().evaluation.metrics["base_vertex_error_cm"].get<double>();
  return out;
}

DemoSeams runDemoSeams(const fs::path& report, const DemoPlan& plan) {
  const fs::path dataset = report / "dataset_tshirt", patchFolder = report / "model_patch",
                 ganFolder = report / "model_gan", tables = report / "paper_tables";
  const garment::Garment shirt = data::datasetGarment(data::readDatasetInfo(dataset));
  const learn::TrainedModel model(patchFolder, shirt);
  DemoSeams out;
  out.data = learn::loadTrainingData(dataset, model.space(), fs::path());
  out.trainSamples = static_cast<int>(out.data.train.size());
  out.epochs = plan.learningEpochs;
  out.pcaComponents = std::min(128, out.trainSamples);

  // The paper's tables: the whole-garment decoder by loss, whole against patches, the fully connected baselines.
  PIXELCLOTH_INFO("demo: the paper's tables (losses, whole against patches, the baselines in three spaces)");
  fs::remove_all(tables);
  auto trainAndMeasureRow = [&](const std::string& name, const std::string& folder, learn::Architecture architecture,
                                learn::ImageLoss loss, double normalWeight, learn::OffsetSpace space) {
    learn::TrainOptions options = smallCnn(architecture, plan.learningEpochs);
    if (architecture != learn::Architecture::Whole) options.model.width = 0.25;
    options.model.pcaComponents = out.pcaComponents;
    options.loss = loss;
    options.normalWeight = normalWeight;
    options.space = space;
    ModelFigures figures;
    figures.name = name;
    figures.folder = tables / folder;
    figures.seconds = learn::train(dataset, figures.folder, options).seconds;
    measureModel(figures, dataset);
    return figures;
  };
  out.table1.push_back(trainAndMeasureRow("L1", "whole_l1", learn::Architecture::Whole, learn::ImageLoss::L1, 0,
                                          learn::OffsetSpace::Local));
  out.table1.push_back(trainAndMeasureRow("L2", "whole_l2", learn::Architecture::Whole, learn::ImageLoss::L2, 0,
                                          learn::OffsetSpace::Local));
  out.table1.push_back(trainAndMeasureRow("L2 + normal", "whole_l2_normal", learn::Architecture::Whole,
                                          learn::ImageLoss::L2, 0.01, learn::OffsetSpace::Local));
  for (const auto& [name, folder] : {std::pair<const char*, const char*>{"whole-garment decoder", "model_whole"},
                                     {"28 patch decoders", "model_patch"}}) {
    ModelFigures figures;
    figures.name = name;
    figures.folder = report / folder;
    measureModel(figures, dataset);
    out.wholeVsPatches.push_back(figures);
  }
  for (const learn::OffsetSpace space :
       {learn::OffsetSpace::Local, learn::OffsetSpace::Root, learn::OffsetSpace::Positions})
    for (const learn::Architecture architecture :
         {learn::Architecture::FullyConnected, learn::Architecture::FullyConnectedPca}) {
      const std::string name =
          std::string(learn::architectureName(architecture)) + ", " + learn::offsetSpaceName(space);
      const std::string folder =
          std::string(learn::architectureName(architecture)) + "_" + learn::offsetSpaceName(space);
      out.table2.push_back(trainAndMeasureRow(name, folder, architecture, learn::ImageLoss::L1, 0, space));
    }

  PIXELCLOTH_INFO("demo: a GAN blender of the patch decoders' stitched predictions");
  out.ganOptions.width = 0.0625;
  out.ganOptions.epochs = 3;
  fs::remove_all(ganFolder);
  out.gan = stitch::trainGan(model, out.data, out.ganOptions, ganFolder);
  out.ganParameters = stitch::ganSummary(out.ganOptions.width)["generator"]["parameters"].get<std::int64_t>();

  PIXELCLOTH_INFO("demo: every stitch mode, k chosen on the regularisation split, measured on the test split");
  auto pca = std::make_shared<stitch::PcaFilter>(stitch::PcaFilter::fit(out.data));
  pca->save(stitch::defaultPcaFolder(patchFolder));
  std::vector<stitch::Stitcher> sweep;
  for (const stitch::StitchMode& mode : stitch::pcaSweepModes(pca->rank())) sweep.emplace_back(shirt, mode, pca);
  std::vector<const stitch::Stitcher*> modes;
  for (const stitch::Stitcher& s : sweep) modes.push_back(&s);
  const std::vector<stitch::Evaluation> chosenOn =
      stitch::evaluate(model, out.data, data::Split::Regularisation, modes);
  out.chosen = chosenOn[stitch::bestPcaMode(chosenOn)].mode;

  stitch::StitchMode mean, feather, gan;
  feather.kind = stitch::StitchKind::Feather;
  gan.kind = stitch::StitchKind::Gan;
  gan.gan = ganFolder;
  std::vector<stitch::Stitcher> final;
  for (const stitch::StitchMode& mode : {mean, feather, out.chosen, gan}) final.emplace_back(shirt, mode, pca);
  // The test split with the sweep too, so the report's plot shows it; the chosen k is the regularisation split's.
  for (const stitch::Stitcher& s : sweep)
    if (s.mode().kind == stitch::StitchKind::Pca && s.mode().components != out.chosen.components)
      final.emplace_back(shirt, s.mode(), pca);
  modes.clear();
  for (const stitch::Stitcher& s : final) modes.push_back(&s);
  out.split = measuredSplit(out.data);
  out.measured = stitch::evaluate(model, out.data, out.split, modes);
  out.exampleRow = out.data.split(out.split).front();
  for (size_t m : {size_t{0}, size_t{2}, size_t{3}})
    out.examples.emplace_back(final[m].mode(),
                              stitch::predictRows(model, out.data, {out.exampleRow}, &final[m]).positions.front());
  return out;
}

garment::ObjImportOptions writeOwnShirtObj(const fs::path& obj) {
  // Each sleeve one tube-shaped UV island cut along the underarm (its vertices hold two UVs there), Z up, in
  // centimetres, its origin 90 cm below and 5 cm behind the body's.
  garment::TShirtOptions shirt;
  shirt.targetVertices = 2000;
  garment::ObjExportOptions file;
  file.tubeSleeves = true;
  file.up = 'z';
  file.scale = 0.01;
  file.translate = Eigen::Vector3d(0, 0.9, 0.05);
  file.shuffleSeed = 7;
  garment::exportGarmentObj(garment::makeTShirt(shirt), obj, file);
  garment::ObjImportOptions placement;
  placement.name = "my_shirt";
  placement.up = 'z';
  placement.scale = 0.01;
  placement.translate = file.translate;
  return placement;
}

OwnGarment runOwnGarment(const fs::path& folder, const body::Body& body, const fs::path& bodyFolder,
                         const DemoPlan& plan) {
  OwnGarment out;
  out.folder = folder;
  out.garmentFolder = folder / "garment";
  fs::remove_all(folder);
  PIXELCLOTH_INFO("demo: a T-shirt OBJ as other programs write it, imported without a cage file");
  fs::create_directories(folder);
  const garment::ObjImportOptions placement = writeOwnShirtObj(folder / "shirt.obj");
  const core::Mesh raw = core::readMesh(folder / "shirt.obj");
  out.fileVertices = raw.numVertices();
  out.fileUvs = static_cast<int>(raw.UV.rows());
  out.fileFaces = raw.numFaces();
  out.garment = garment::importGarmentObj(folder / "shirt.obj", placement, &out.import);
  out.piecePatches = static_cast<int>(patches::garmentPatches(out.garment).size());
  // `garment --import ... --fit-to BODY`: the body loops, centre lines and splits that give it patches.
  out.fit = patches::fitGarmentToBody(out.garment, body);
  garment::saveGarment(out.garmentFolder, out.garment);
  out.dressing = cage::dressGarment(body, cage::bodyCage(body), out.garment, cage::garmentCage(out.garment));

  PIXELCLOTH_INFO("demo: the imported garment simulated, checked, rebuilt from markers");
  const fs::path dataset = folder / "dataset";
  // The folder, as `generate --garment DIR` takes it.
  out.dataset = simulateDataset(dataset, bodyFolder, out.garmentFolder.string(), plan.ownGarmentSamples, plan.seed);
  recon::DatasetReconstructionOptions options;
  options.split.reset();  // every row
  options.meshes = 1;
  out.reconstruction = recon::reconstructDataset(dataset, folder / "reconstruction", options);

  PIXELCLOTH_INFO("demo: per-patch decoders of the imported garment trained, predicted and evaluated");
  // The paper's per-patch decoders (section 5), as small as the template's in the learning section.
  out.data = learn::loadTrainingData(dataset, learn::OffsetSpace::Local, {});
  out.shown = firstRows(out.data, measuredSplit(out.data));
  out.model.name = "patch";
  out.model.label = "per-patch decoders, pose in";
  out.model.folder = folder / "model_patch";
  out.model.options = smallCnn(learn::Architecture::Patch, plan.learningEpochs);
  out.model = trainAndMeasure(std::move(out.model), dataset, fs::path(), out.shown);
  return out;
}

}  // namespace pixelcloth::eval
