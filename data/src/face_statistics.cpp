#include "pixelcloth/data/face_statistics.h"

#include <vector>

#include "pixelcloth/core/geometry.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/core/self_intersection.h"

namespace pixelcloth::data {

FaceStatistics faceStatistics(const Dataset& dataset) {
  const garment::Garment garment = datasetGarment(dataset.info);
  const int faces = garment.mesh.numFaces();
  FaceStatistics stats;
  stats.samples = dataset.rows();
  stats.minAreaRatio = Eigen::VectorXd::Constant(faces, dataset.rows() > 0 ? 1e300 : 1.0);
  stats.maxAreaRatio = Eigen::VectorXd::Constant(faces, dataset.rows() > 0 ? 0.0 : 1.0);
  Eigen::VectorXd counts = Eigen::VectorXd::Zero(faces);
  std::vector<char> hit(faces);
  core::Progress progress("face statistics", dataset.rows());
  for (int row = 0; row < dataset.rows(); ++row) {
    const Eigen::MatrixX3d x = dataset.positionsOf(row).cast<double>();
    const Eigen::VectorXd ratio = core::areaRatios(x, garment.mesh);
    stats.minAreaRatio = stats.minAreaRatio.cwiseMin(ratio);
    stats.maxAreaRatio = stats.maxAreaRatio.cwiseMax(ratio);
    std::fill(hit.begin(), hit.end(), 0);
    const std::vector<std::pair<int, int>> pairs = core::selfIntersections(x, garment.mesh.F);
    for (const auto& [f, g] : pairs) hit[f] = hit[g] = 1;
    for (int f = 0; f < faces; ++f) counts(f) += hit[f];
    stats.samplesSelfIntersecting += !pairs.empty();
    progress.advance();
  }
  stats.selfIntersection = dataset.rows() > 0 ? Eigen::VectorXd(counts / dataset.rows()) : counts;
  return stats;
}

}  // namespace pixelcloth::data
