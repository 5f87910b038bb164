#include "pixelcloth/stitch/seams.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh.h"

namespace pixelcloth::stitch {

namespace {

/// Vertices within `rings` mesh edges of `seeds`, sorted.
std::vector<int> rings(const std::vector<std::vector<int>>& adjacency, const std::vector<int>& seeds, int count) {
  std::set<int> reached(seeds.begin(), seeds.end());
  std::vector<int> front(reached.begin(), reached.end());
  for (int ring = 0; ring < count; ++ring) {
    std::vector<int> next;
    for (int v : front)
      for (int w : adjacency[v])
        if (reached.insert(w).second) next.push_back(w);
    front = std::move(next);
  }
  return {reached.begin(), reached.end()};
}

nlohmann::json meanOrNull(double sum, long long count) {
  return count > 0 ? nlohmann::json(sum / static_cast<double>(count)) : nlohmann::json();
}

/// Per vertex: the largest distance between two networks' predictions (the diameter of the predicted points, metres),
/// and how many networks predict it.
void vertexGaps(const std::vector<PredictedPositions>& separate, int V, Eigen::VectorXd& gap, Eigen::VectorXi& count) {
  gap = Eigen::VectorXd::Zero(V);
  count = Eigen::VectorXi::Zero(V);
  std::vector<std::vector<Eigen::RowVector3d>> points(V);
  for (const PredictedPositions& p : separate) {
    PIXELCLOTH_CHECK(p.vertices != nullptr && p.positions.rows() == static_cast<Eigen::Index>(p.vertices->size()),
                     "seams: a prediction's positions do not match its vertices");
    for (size_t i = 0; i < p.vertices->size(); ++i) {
      const int v = (*p.vertices)[i];
      PIXELCLOTH_CHECK(v >= 0 && v < V, "seams: vertex " << v << " of a garment of " << V);
      for (const Eigen::RowVector3d& q : points[v]) gap(v) = std::max(gap(v), (q - p.positions.row(i)).norm());
      points[v].push_back(p.positions.row(static_cast<Eigen::Index>(i)));
      ++count(v);
    }
  }
}

}  // namespace

double foldAngleDeg(const Eigen::MatrixX3d& faceNormals, const std::array<int, 2>& pair) {
  const double c = std::clamp(faceNormals.row(pair[0]).dot(faceNormals.row(pair[1])), -1.0, 1.0);
  return std::acos(c) * 180.0 / M_PI;
}

SeamLayout::SeamLayout(const garment::Garment& garment)
    : F_(garment.mesh.F), numVertices_(garment.mesh.numVertices()) {
  const cage::Cage cage = cage::garmentCage(garment);
  std::map<std::pair<int, int>, std::vector<int>> edgeFaces;
  std::vector<std::vector<int>> adjacency(numVertices_);
  for (Eigen::Index f = 0; f < F_.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = F_(f, c), b = F_(f, (c + 1) % 3);
      edgeFaces[std::minmax(a, b)].push_back(static_cast<int>(f));
      adjacency[a].push_back(b);
      adjacency[b].push_back(a);
    }
  std::set<int> near, cageVertices;
  for (const cage::CageCurve& c : cage.curves) {
    SeamCurve curve{c.name, c.kind, c.vertices, {}, {}};
    const size_t n = c.vertices.size();
    for (size_t i = 0; i + 1 < n + (c.closed ? 1 : 0); ++i) {
      const auto found = edgeFaces.find(std::minmax(c.vertices[i], c.vertices[(i + 1) % n]));
      PIXELCLOTH_ASSERT(found != edgeFaces.end(), "cage curve " << c.name << " leaves the mesh edges");
      if (found->second.size() == 2) curve.facePairs.push_back({found->second[0], found->second[1]});
    }
    curve.near = rings(adjacency, c.vertices, 2);
    if (c.kind != cage::CurveKind::Opening) near.insert(curve.near.begin(), curve.near.end());
    cageVertices.insert(c.vertices.begin(), c.vertices.end());
    curves_.push_back(std::move(curve));
  }
  nearSeam_.assign(near.begin(), near.end());
  cageVertices_.assign(cageVertices.begin(), cageVertices.end());
  for (int v = 0; v < numVertices_; ++v)
    if (!near.count(v)) interior_.push_back(v);
}

double meanSeamGapCm(const SeamLayout& layout, const std::vector<PredictedPositions>& separate) {
  Eigen::VectorXd gap;
  Eigen::VectorXi count;
  vertexGaps(separate, layout.numVertices(), gap, count);
  double sum = 0;
  int shared = 0;
  for (int v : layout.cageVertices())
    if (count(v) >= 2) {
      sum += 100 * gap(v);
      ++shared;
    }
  return shared > 0 ? sum / shared : std::numeric_limits<double>::quiet_NaN();
}

SeamMetrics::SeamMetrics(const SeamLayout& layout)
    : layout_(&layout), curves_(layout.curves().size()), shared_(layout.curves().size(), 0) {}

void SeamMetrics::add(const std::vector<PredictedPositions>& separate, const Eigen::MatrixX3d& blended,
                      const Eigen::MatrixX3d& truth) {
  const int V = layout_->numVertices();
  PIXELCLOTH_CHECK(blended.rows() == V && truth.rows() == V,
                   "seams: " << blended.rows() << " blended and " << truth.rows() << " true vertices, expected " << V);
  Eigen::VectorXd gap;
  Eigen::VectorXi count;
  vertexGaps(separate, V, gap, count);
  const Eigen::VectorXd error = 100 * (blended - truth).rowwise().norm();
  const Eigen::MatrixX3d nBlended = core::faceNormals(blended, layout_->faces()),
                         nTruth = core::faceNormals(truth, layout_->faces());
  for (size_t c = 0; c < curves_.size(); ++c) {
    const SeamCurve& curve = layout_->curves()[c];
    Sum& sum = curves_[c];
    shared_[c] = 0;
    for (int v : curve.vertices)
      if (count(v) >= 2) {
        ++shared_[c];
        sum.gap += 100 * gap(v);
        sum.gapMax = std::max(sum.gapMax, 100 * gap(v));
        ++sum.gapCount;
      }
    for (const std::array<int, 2>& pair : curve.facePairs) {
      const double jump = std::abs(foldAngleDeg(nBlended, pair) - foldAngleDeg(nTruth, pair));
      sum.jump += jump;
      ++sum.jumpCount;
      all_.jump += jump;
      ++all_.jumpCount;
    }
    for (int v : curve.near) sum.nearError += error(v);
    sum.nearCount += static_cast<long long>(curve.near.size());
  }
  for (int v : layout_->cageVertices())
    if (count(v) >= 2) {
      all_.gap += 100 * gap(v);
      all_.gapMax = std::max(all_.gapMax, 100 * gap(v));
      ++all_.gapCount;
    }
  for (int v : layout_->nearSeam()) all_.nearError += error(v);
  all_.nearCount += static_cast<long long>(layout_->nearSeam().size());
  for (int v : layout_->interior()) interiorError_ += error(v);
  interiorCount_ += static_cast<long long>(layout_->interior().size());
  ++samples_;
}

nlohmann::json SeamMetrics::toJson() const {
  const auto gapJson = [](const Sum& s) {
    return s.gapCount > 0 ? nlohmann::json{{"mean", s.gap / static_cast<double>(s.gapCount)}, {"max", s.gapMax}}
                          : nlohmann::json{{"mean", nullptr}, {"max", nullptr}};
  };
  nlohmann::json curves = nlohmann::json::array();
  for (size_t c = 0; c < curves_.size(); ++c) {
    const SeamCurve& curve = layout_->curves()[c];
    curves.push_back({{"name", curve.name},
                      {"kind", garment::curveKindName(curve.kind)},
                      {"vertices", curve.vertices.size()},
                      {"shared_vertices", shared_[c]},
                      {"gap_cm", gapJson(curves_[c])},
                      {"normal_jump_deg", meanOrNull(curves_[c].jump, curves_[c].jumpCount)},
                      {"near_seam_error_cm", meanOrNull(curves_[c].nearError, curves_[c].nearCount)}});
  }
  return {{"samples", samples_},
          {"gap_cm", gapJson(all_)},
          {"normal_jump_deg", meanOrNull(all_.jump, all_.jumpCount)},
          {"near_seam_error_cm", meanOrNull(all_.nearError, all_.nearCount)},
          {"interior_error_cm", meanOrNull(interiorError_, interiorCount_)},
          {"curves", curves}};
}

}  // namespace pixelcloth::stitch
