#include "pixelcloth/learn/training_data.h"

#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/data/base_set.h"

namespace pixelcloth::learn {

const std::vector<int>& TrainingData::split(data::Split which) const {
  switch (which) {
    case data::Split::Train:
      return train;
    case data::Split::Regularisation:
      return regularisation;
    case data::Split::Test:
      return test;
  }
  PIXELCLOTH_FAIL("split " << static_cast<int>(which) << ", expected train, regularisation or test");
}

TrainingData loadTrainingData(const data::DatasetFolder& where, OffsetSpace space,
                              const std::filesystem::path& baseFolder) {
  const std::filesystem::path& folder = where.path;
  const data::Dataset dataset = data::openDataset(where);
  TrainingData out;
  out.folder = folder;
  out.info = dataset.info;
  out.manifestCrc = data::fileCrc32(folder / "manifest.json");
  out.garment = data::datasetGarment(dataset.info);
  out.space = space;
  out.poseSize = dataset.info.settings.poseSize;
  const body::Body body = data::loadDatasetBody(where);
  const garment::Embedding embedding = data::loadDatasetEmbedding(where, body.mesh.F.rows());
  data::BaseSet base;
  if (!baseFolder.empty()) {
    base = data::openBaseSet(baseFolder, dataset.info);
    out.baseFolder = baseFolder;
    out.baseCrc = data::fileCrc32(baseFolder / "manifest.json");
    out.markers = base.markers;
  }
  const int rows = dataset.rows();
  out.inputs.resize(rows, out.poseSize + 3 * out.markers);
  for (int r = 0; r < rows; ++r) {
    const Eigen::VectorXf pose = dataset.pose(r);
    out.inputs.row(r).head(out.poseSize) = pose.transpose();
    if (out.markers > 0) out.inputs.row(r).tail(3 * out.markers) = base.featuresOf(r).transpose();
    const std::string context = folder.string() + ": pose of row " + std::to_string(r);
    const Eigen::MatrixX3d posed = body.posedVertices(body::Pose::fromLeading(pose, context));
    garment::EmbeddedFrames frames = garment::embeddedFrames(posed, body.mesh.F, embedding);
    const Eigen::MatrixX3d truth = dataset.positionsOf(r).cast<double>();
    Eigen::MatrixX3f values = valuesInSpace(space, frames, truth);
    if (out.residual()) {
      const Eigen::MatrixX3f baseValues =
          valuesInSpace(space, frames, garment::positionsFromOffsets(frames, base.offsetsOf(r).cast<double>()));
      values -= baseValues;
      out.base.push_back(baseValues);
    }
    out.values.push_back(values);
    out.truth.push_back(truth.cast<float>());
    out.frames.push_back(std::move(frames));
  }
  out.train = dataset.rowsOf(data::Split::Train);
  out.regularisation = dataset.rowsOf(data::Split::Regularisation);
  out.test = dataset.rowsOf(data::Split::Test);
  return out;
}

}  // namespace pixelcloth::learn
