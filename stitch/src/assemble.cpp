#include "pixelcloth/stitch/assemble.h"

#include "pixelcloth/core/error.h"

namespace pixelcloth::stitch {

Eigen::VectorXi coverage(const std::vector<learn::NetworkPrediction>& predictions, int numVertices) {
  Eigen::VectorXi count = Eigen::VectorXi::Zero(numVertices);
  for (const learn::NetworkPrediction& p : predictions)
    for (int v : p.vertices) {
      PIXELCLOTH_CHECK(v >= 0 && v < numVertices, "assemble: vertex " << v << " of a garment of " << numVertices);
      ++count(v);
    }
  return count;
}

Eigen::MatrixXf assembleMean(const std::vector<learn::NetworkPrediction>& predictions, int numVertices) {
  PIXELCLOTH_CHECK(!predictions.empty(), "assemble: no predictions");
  const Eigen::Index batch = predictions.front().values.rows();
  const Eigen::VectorXi count = coverage(predictions, numVertices);
  for (int v = 0; v < numVertices; ++v)
    PIXELCLOTH_CHECK(count(v) > 0, "assemble: no network predicts vertex " << v << " (a patch model without all its "
                                                                           "patches? train the missing ones)");
  Eigen::MatrixXf sum = Eigen::MatrixXf::Zero(batch, 3 * numVertices);
  for (const learn::NetworkPrediction& p : predictions) {
    PIXELCLOTH_CHECK(p.values.rows() == batch && p.values.cols() == 3 * static_cast<Eigen::Index>(p.vertices.size()),
                     "assemble: a prediction of " << p.values.rows() << " x " << p.values.cols() << " values for "
                                                  << p.vertices.size() << " vertices");
    for (size_t i = 0; i < p.vertices.size(); ++i) sum.middleCols<3>(3 * p.vertices[i]) += p.values.middleCols<3>(3 * i);
  }
  for (int v = 0; v < numVertices; ++v) sum.middleCols<3>(3 * v) /= static_cast<float>(count(v));
  return sum;
}

}  // namespace pixelcloth::stitch
