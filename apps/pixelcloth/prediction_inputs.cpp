#include "prediction_inputs.h"

#include <algorithm>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/recon/capture_base.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace fs = std::filesystem;

namespace {

/// The model folder's model, for the garment of `dataset`, checked against it.
std::unique_ptr<learn::TrainedModel> modelFor(const fs::path& modelFolder, const data::DatasetInfo& info,
                                              learn::Engine engine) {
  auto model = std::make_unique<learn::TrainedModel>(modelFolder, data::datasetGarment(info), engine);
  model->checkDataset(info);
  return model;
}

}  // namespace

void addEngineOption(CLI::App& verb, std::string& engine) {
  verb.add_option("--engine", engine,
                  "What runs the networks: onednn (compiled once, fast) or libtorch (its modules, the reference)")
      ->capture_default_str()
      ->check(CLI::IsMember({"onednn", "libtorch"}));
}

void addStitchOptions(CLI::App& verb, StitchArgs& args, bool several) {
  verb.add_option("--stitch", args.modes,
                  std::string("How the patch networks' predictions become one garment: mean, feather (weights falling "
                              "off outside each patch), pca:K (the mean projected on K principal components of the "
                              "training split) or gan:DIR (a blender from train --model gan)") +
                      (several ? "; several separated by commas, each measured on the same predictions" : ""))
      ->capture_default_str();
  verb.add_option("--pca", args.pca,
                  "PCA filter folder for pca:K (pixelcloth pca); default: the model folder's pca/, fitted on the "
                  "dataset's train split on first use");
  verb.add_option("--pca-rank", args.pcaRank,
                  "Components kept when the filter is fitted here (0: min(2048, train samples, 3 x vertices))")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

std::vector<stitch::Stitcher> makeStitchers(const StitchArgs& args, const PredictionInputs& inputs) {
  const std::vector<stitch::StitchMode> modes = stitch::parseStitchModes(args.modes, "--stitch");
  std::shared_ptr<const stitch::PcaFilter> pca;
  const bool needPca = std::any_of(modes.begin(), modes.end(),
                                   [](const stitch::StitchMode& m) { return m.kind == stitch::StitchKind::Pca; });
  const learn::TrainingData& data = inputs.data;
  if (needPca && !args.pca.empty()) {
    auto filter = std::make_shared<stitch::PcaFilter>(stitch::PcaFilter::load(args.pca));
    if (data.train.empty())  // one pose: no dataset rows to check against
      filter->checkMatches(data.garment.name, data.garment.mesh.numVertices(), data.space);
    else
      filter->checkMatches(data);
    pca = std::move(filter);
  } else if (needPca) {
    const fs::path folder = stitch::defaultPcaFolder(inputs.model->folder());
    if (fs::is_regular_file(folder / "pca.json")) {
      auto filter = std::make_shared<stitch::PcaFilter>(stitch::PcaFilter::load(folder));
      bool matches = true;
      try {
        if (!data.train.empty()) filter->checkMatches(data);
      } catch (const core::InputError& e) {
        matches = false;
        PIXELCLOTH_INFO(folder.string() << ": fitted on another dataset; fitting again on " << data.folder.string());
      }
      if (matches && args.pcaRank != 0 && args.pcaRank != filter->rank()) matches = false;
      if (matches) pca = std::move(filter);
    }
    if (!pca) {
      PIXELCLOTH_CHECK(!data.train.empty(), "--stitch pca:K: " << folder.string()
                                                                << " holds no PCA filter of this model's dataset; "
                                                                   "fit one with pixelcloth pca or evaluate "
                                                                   "--stitch pca:K first, or give --pca DIR");
      stitch::PcaFilter filter = stitch::PcaFilter::fit(data, args.pcaRank);
      filter.save(folder);
      pca = std::make_shared<stitch::PcaFilter>(std::move(filter));
    }
  }
  std::vector<stitch::Stitcher> stitchers;
  for (const stitch::StitchMode& mode : modes) stitchers.emplace_back(data.garment, mode, pca);
  return stitchers;
}

PredictionInputs datasetPredictionInputs(const fs::path& modelFolder, const fs::path& dataset, const fs::path& base,
                                         learn::Engine engine) {
  const data::DatasetInfo info = data::readDatasetInfo(dataset);
  PredictionInputs out;
  out.model = modelFor(modelFolder, info, engine);
  PIXELCLOTH_CHECK(base.empty() || out.model->residual(),
                   "--base " << base.string() << ": the model in " << modelFolder.string()
                             << " is not a residual model (it takes the pose alone)");
  const fs::path baseFolder = out.model->residual() ? (base.empty() ? out.model->baseFolder() : base) : fs::path();
  out.data = learn::loadTrainingData(dataset, out.model->space(), baseFolder);
  return out;
}

PredictionInputs posePredictionInputs(const fs::path& modelFolder, const fs::path& posePath, const fs::path& markersPath,
                                      const fs::path& datasetArg, learn::Engine engine) {
  const fs::path dataset = datasetArg.empty() ? learn::trainingDatasetOf(modelFolder) : datasetArg;
  const data::DatasetInfo info = data::readDatasetInfo(dataset);
  PredictionInputs out;
  out.model = modelFor(modelFolder, info, engine);
  learn::TrainingData& data = out.data;
  data.folder = dataset;
  data.info = info;
  data.garment = data::datasetGarment(info);
  data.space = out.model->space();
  data.poseSize = out.model->poseSize();
  const body::Pose pose = body::readPose(posePath, poseLimits());
  const Eigen::VectorXf vector = pose.toVector().head(data.poseSize);
  PIXELCLOTH_CHECK(pose.toVector().tail(body::kPoseSize - data.poseSize).isApprox(
                       body::Pose::fromLeading(vector).toVector().tail(body::kPoseSize - data.poseSize)) ||
                       data.poseSize == body::kPoseSize,
                   posePath.string() << ": the " << data.garment.name << " model takes the first " << data.poseSize
                                     << " pose floats; this pose also turns later joints");
  const body::Body body = data::loadDatasetBody(dataset);
  const garment::Embedding embedding = data::loadDatasetEmbedding(dataset, body.mesh.F.rows());
  data.frames.push_back(garment::embeddedFrames(body.posedVertices(body::Pose::fromLeading(vector)), body.mesh.F, embedding));
  data.truth.push_back(Eigen::MatrixXf::Constant(data.garment.mesh.numVertices(), 3, std::nanf("")));
  data.values.push_back(Eigen::MatrixXf::Zero(data.garment.mesh.numVertices(), 3));
  if (out.model->residual()) {
    PIXELCLOTH_CHECK(!markersPath.empty(), "predict: the model in " << modelFolder.string()
                                                                    << " is a residual model: give the garment's "
                                                                       "markers too (--markers M.json)");
    const recon::CaptureBase base =
        recon::baseOfCapture(out.model->baseFolder(), dataset, cage::readMarkers(markersPath),
                             body::Pose::fromLeading(vector), markersPath.string());
    data.baseFolder = out.model->baseFolder();
    data.markers = static_cast<int>(base.features.size() / 3);
    data.base.push_back(learn::valuesInSpace(data.space, data.frames.front(),
                                             garment::positionsFromOffsets(data.frames.front(), base.offsets)));
    data.inputs.resize(1, data.poseSize + base.features.size());
    data.inputs << vector.transpose(), base.features.transpose().cast<float>();
  } else {
    PIXELCLOTH_CHECK(markersPath.empty(), "--markers " << markersPath.string() << ": the model in "
                                                       << modelFolder.string() << " takes the pose alone");
    data.inputs = vector.transpose();
  }
  data.test = {0};
  return out;
}

}  // namespace pixelcloth::apps
