#include "pixelcloth/stitch/assemble.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <set>

#include "pixelcloth/core/error.h"
#include "pixelcloth/patches/patch.h"

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
    PIXELCLOTH_CHECK(count(v) > 0, "assemble: no network predicts vertex " << v + 1 << " (a patch model without all its "
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

namespace pixelcloth::stitch {

FeatherAssembler::FeatherAssembler(const garment::Garment& garment) : numVertices_(garment.mesh.numVertices()) {
  for (const patches::Patch& patch : patches::garmentPatches(garment)) ownVertices_.push_back(patch.vertices);
  neighbours_.resize(numVertices_);
  const Eigen::MatrixX3i& F = garment.mesh.F;
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) edges.insert(std::minmax(F(f, c), F(f, (c + 1) % 3)));
  for (const auto& [a, b] : edges) {
    const double length = (garment.mesh.V.row(a) - garment.mesh.V.row(b)).norm();
    neighbours_[a].emplace_back(b, length);
    neighbours_[b].emplace_back(a, length);
  }
}

Eigen::VectorXf FeatherAssembler::weights(const learn::NetworkPrediction& prediction) const {
  const std::vector<int>& covered = prediction.vertices;
  if (prediction.patch < 0) return Eigen::VectorXf::Ones(static_cast<Eigen::Index>(covered.size()));
  PIXELCLOTH_CHECK(prediction.patch < static_cast<int>(ownVertices_.size()),
                   "assemble: patch " << prediction.patch << " of a garment of " << ownVertices_.size() << " patches");
  // Dijkstra from the patch's own vertices over the edges between covered vertices.
  std::vector<double> distance(numVertices_, std::numeric_limits<double>::infinity());
  std::vector<char> inCrop(numVertices_, 0);
  for (int v : covered) {
    PIXELCLOTH_CHECK(v >= 0 && v < numVertices_, "assemble: vertex " << v << " of a garment of " << numVertices_);
    inCrop[v] = 1;
  }
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (int v : ownVertices_[prediction.patch])
    if (inCrop[v]) {
      distance[v] = 0;
      queue.emplace(0.0, v);
    }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;
    for (const auto& [w, length] : neighbours_[v])
      if (inCrop[w] && d + length < distance[w]) {
        distance[w] = d + length;
        queue.emplace(distance[w], w);
      }
  }
  double reach = 0;
  for (int v : covered)
    if (std::isfinite(distance[v])) reach = std::max(reach, distance[v]);
  Eigen::VectorXf weight(static_cast<Eigen::Index>(covered.size()));
  for (size_t i = 0; i < covered.size(); ++i) {
    const double d = distance[covered[i]];
    // Smoothstep from 1 on the patch to 0 at the crop's farthest vertex; a covered vertex cut off from the patch
    // (across a layout edge) gets none.
    const double x = !std::isfinite(d) ? 0.0 : reach > 0 ? 1.0 - d / reach : 1.0;
    weight(static_cast<Eigen::Index>(i)) = static_cast<float>(x * x * (3 - 2 * x));
  }
  return weight;
}

Eigen::MatrixXf FeatherAssembler::assemble(const std::vector<learn::NetworkPrediction>& predictions) const {
  PIXELCLOTH_CHECK(!predictions.empty(), "assemble: no predictions");
  const Eigen::Index batch = predictions.front().values.rows();
  Eigen::MatrixXf sum = Eigen::MatrixXf::Zero(batch, 3 * numVertices_);
  Eigen::VectorXf total = Eigen::VectorXf::Zero(numVertices_);
  for (const learn::NetworkPrediction& p : predictions) {
    PIXELCLOTH_CHECK(p.values.rows() == batch && p.values.cols() == 3 * static_cast<Eigen::Index>(p.vertices.size()),
                     "assemble: a prediction of " << p.values.rows() << " x " << p.values.cols() << " values for "
                                                  << p.vertices.size() << " vertices");
    const Eigen::VectorXf w = weights(p);
    for (size_t i = 0; i < p.vertices.size(); ++i) {
      const float wi = w(static_cast<Eigen::Index>(i));
      sum.middleCols<3>(3 * p.vertices[i]) += wi * p.values.middleCols<3>(3 * i);
      total(p.vertices[i]) += wi;
    }
  }
  for (int v = 0; v < numVertices_; ++v) {
    PIXELCLOTH_CHECK(total(v) > 0, "assemble: no network predicts vertex " << v + 1 << " (a patch model without all its "
                                                                           "patches? train the missing ones)");
    sum.middleCols<3>(3 * v) /= total(v);
  }
  return sum;
}

}  // namespace pixelcloth::stitch
