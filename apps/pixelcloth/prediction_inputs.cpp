#include "prediction_inputs.h"

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/recon/capture_base.h"

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
  const body::Pose pose = body::readPose(posePath);
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
