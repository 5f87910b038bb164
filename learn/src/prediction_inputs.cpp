#include "pixelcloth/learn/prediction_inputs.h"

#include <cmath>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/embedding.h"

namespace pixelcloth::learn {

namespace fs = std::filesystem;

namespace {
/// The model folder's model, for the garment of `info`'s dataset, checked against it.
std::unique_ptr<TrainedModel> modelFor(const fs::path& modelFolder, const data::DatasetInfo& info, Engine engine) {
  auto model = std::make_unique<TrainedModel>(modelFolder, data::datasetGarment(info), engine);
  model->checkDataset(info);
  return model;
}
}  // namespace

PredictionInputs datasetPredictionInputs(const fs::path& modelFolder, const data::DatasetFolder& dataset,
                                         const fs::path& base, Engine engine) {
  const data::DatasetInfo info = data::readDatasetInfo(dataset);
  PredictionInputs out;
  out.model = modelFor(modelFolder, info, engine);
  PIXELCLOTH_CHECK(base.empty() || out.model->residual(),
                   "--base " << base.string() << ": the model in " << modelFolder.string()
                             << " is not a residual model (it takes the pose alone)");
  const fs::path baseFolder = out.model->residual() ? (base.empty() ? out.model->baseFolder() : base) : fs::path();
  out.data = loadTrainingData(dataset, out.model->space(), baseFolder);
  return out;
}

PredictionInputs posePredictionInputs(const fs::path& modelFolder, const body::Pose& pose, const std::string& poseName,
                                      const data::DatasetFolder& dataset, Engine engine) {
  return posesPredictionInputs(modelFolder, {pose}, poseName, dataset, engine);
}

PredictionInputs posesPredictionInputs(const fs::path& modelFolder, const std::vector<body::Pose>& poses,
                                       const std::string& name, const data::DatasetFolder& datasetArg, Engine engine) {
  PIXELCLOTH_CHECK(!poses.empty(), name << ": no poses");
  const data::DatasetFolder dataset =
      datasetArg.path.empty() ? datasetArg.with(trainingDatasetOf(modelFolder)) : datasetArg;
  return posesPredictionInputs(modelFor(modelFolder, data::readDatasetInfo(dataset), engine), poses, name, dataset);
}

PredictionInputs posesPredictionInputs(std::unique_ptr<TrainedModel> model, const std::vector<body::Pose>& poses,
                                       const std::string& name, const data::DatasetFolder& dataset) {
  PIXELCLOTH_CHECK(!poses.empty(), name << ": no poses");
  const data::DatasetInfo info = data::readDatasetInfo(dataset);
  model->checkDataset(info);
  PredictionInputs out;
  out.model = std::move(model);
  TrainingData& data = out.data;
  data.folder = dataset.path;
  data.info = info;
  data.garment = data::datasetGarment(info);
  data.space = out.model->space();
  data.poseSize = out.model->poseSize();
  const body::Body body = data::loadDatasetBody(dataset);
  const garment::Embedding embedding = data::loadDatasetEmbedding(dataset, body.mesh.F.rows());
  const int V = data.garment.mesh.numVertices();
  const int rest = body::kPoseSize - data.poseSize;
  data.inputs.resize(static_cast<Eigen::Index>(poses.size()), data.poseSize);
  core::Progress progress("posed frames", static_cast<std::int64_t>(poses.size()));
  for (size_t k = 0; k < poses.size(); ++k) {
    const Eigen::VectorXf full = poses[k].toVector();
    const Eigen::VectorXf vector = full.head(data.poseSize);
    PIXELCLOTH_CHECK(rest == 0 || full.tail(rest).isApprox(body::Pose::fromLeading(vector).toVector().tail(rest)),
                     name << (poses.size() > 1 ? ": frame " + std::to_string(k) : std::string()) << ": the "
                          << data.garment.name << " model takes the first " << data.poseSize
                          << " pose floats; this pose also turns later joints");
    data.frames.push_back(
        garment::embeddedFrames(body.posedVertices(body::Pose::fromLeading(vector)), body.mesh.F, embedding));
    data.truth.push_back(Eigen::MatrixXf::Constant(V, 3, std::nanf("")));
    data.values.push_back(Eigen::MatrixXf::Zero(V, 3));
    data.inputs.row(static_cast<Eigen::Index>(k)) = vector.transpose();
    data.test.push_back(static_cast<int>(k));
    progress.advance();
  }
  progress.finish();
  return out;
}

void addPoseBase(PredictionInputs& inputs, const Eigen::MatrixX3d& baseOffsets, const Eigen::VectorXd& features) {
  addPoseBases(inputs, {baseOffsets}, features.transpose());
}

void addPoseBases(PredictionInputs& inputs, const std::vector<Eigen::MatrixX3d>& baseOffsets,
                  const Eigen::MatrixXd& features) {
  TrainingData& data = inputs.data;
  const Eigen::Index rows = data.rows();
  PIXELCLOTH_CHECK(inputs.model->residual() && data.base.empty() &&
                       static_cast<Eigen::Index>(baseOffsets.size()) == rows && features.rows() == rows &&
                       features.cols() % 3 == 0,
                   "addPoseBases: a residual model's pose rows without their base, and one base and feature row "
                   "for each, expected");
  data.baseFolder = inputs.model->baseFolder();
  data.markers = static_cast<int>(features.cols() / 3);
  for (Eigen::Index r = 0; r < rows; ++r)
    data.base.push_back(
        valuesInSpace(data.space, data.frames[r], garment::positionsFromOffsets(data.frames[r], baseOffsets[r])));
  const Eigen::MatrixXf poses = data.inputs;
  data.inputs.resize(rows, poses.cols() + features.cols());
  data.inputs << poses, features.cast<float>();
}

}  // namespace pixelcloth::learn
