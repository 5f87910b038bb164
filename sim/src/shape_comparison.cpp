#include "pixelcloth/sim/shape_comparison.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "pixelcloth/core/error.h"
#include "pixelcloth/patches/frame.h"
#include "pixelcloth/patches/raster.h"

namespace pixelcloth::sim {

namespace {

bool sameMesh(const garment::Garment& a, const garment::Garment& b) {
  return a.mesh.numVertices() == b.mesh.numVertices() && a.mesh.F.rows() == b.mesh.F.rows() && a.mesh.F == b.mesh.F;
}

/// Per layout of `b`: the operator that rasterises `a` in that layout's frame and the one that samples such an image
/// at `b`'s vertices.
struct PatternMap {
  std::vector<patches::RasterOperator> rasters;
  std::vector<patches::SampleOperator> samples;
};

PatternMap patternMap(const garment::Garment& a, const garment::Garment& b, int size) {
  PatternMap map;
  for (int lb = 0; lb < b.numLayouts(); ++lb) {
    const auto found = std::find(a.layouts.begin(), a.layouts.end(), b.layouts[lb]);
    PIXELCLOTH_CHECK(found != a.layouts.end(), "compare: garment " << b.name << " has a layout '" << b.layouts[lb]
                                                                   << "' that garment " << a.name
                                                                   << " lacks: not meshes of one pattern");
    const int la = static_cast<int>(found - a.layouts.begin());
    const patches::ImageFrame frame = patches::layoutFrame(a, la, size);
    patches::RasterOperator raster = patches::buildRaster(a, la, frame);
    // Sample a's image at b's vertices of the layout: b's own raster names them, a's mask says which pixels hold a.
    patches::RasterOperator probe = raster;
    probe.layout = lb;
    probe.vertices.clear();
    for (int v = 0; v < b.mesh.numVertices(); ++v)
      if (b.vertexUV(v, lb) >= 0) probe.vertices.push_back(v);
    map.samples.push_back(patches::buildSample(b, probe));
    map.rasters.push_back(std::move(raster));
  }
  return map;
}

Eigen::VectorXd sampledDistances(const PatternMap& map, const Eigen::MatrixX3d& xa, const Eigen::MatrixX3d& xb) {
  const int n = static_cast<int>(xb.rows());
  Eigen::MatrixX3d sum = Eigen::MatrixX3d::Zero(n, 3);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(n);
  const Eigen::MatrixXf values = xa.cast<float>();
  for (size_t l = 0; l < map.rasters.size(); ++l) {
    const Eigen::MatrixXf image = map.rasters[l].apply(values);
    const Eigen::MatrixXf sampled = map.samples[l].apply(image);
    for (const int v : map.samples[l].vertices) {
      if (map.samples[l].matrix.row(v).nonZeros() == 0) continue;  // no pixel of a's layout near it
      sum.row(v) += sampled.row(v).cast<double>();
      count(v) += 1;
    }
  }
  Eigen::VectorXd d = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  for (int v = 0; v < n; ++v)
    if (count(v) > 0) d(v) = (sum.row(v) / count(v) - xb.row(v)).norm();
  return d;
}

Eigen::VectorXd vertexDistances(const Eigen::MatrixX3d& xa, const Eigen::MatrixX3d& xb) {
  return (xa - xb).rowwise().norm();
}

void checkPositions(const garment::Garment& g, const Eigen::MatrixX3d& x) {
  PIXELCLOTH_CHECK(x.rows() == g.mesh.numVertices(), "compare: " << x.rows() << " positions for garment " << g.name
                                                                 << " of " << g.mesh.numVertices() << " vertices");
}

}  // namespace

Eigen::VectorXd distancesThroughPattern(const garment::Garment& a, const Eigen::MatrixX3d& xa,
                                        const garment::Garment& b, const Eigen::MatrixX3d& xb, int size) {
  checkPositions(a, xa);
  checkPositions(b, xb);
  if (sameMesh(a, b)) return vertexDistances(xa, xb);
  return sampledDistances(patternMap(a, b, size), xa, xb);
}

DistanceSummary summarise(const Eigen::VectorXd& distances) {
  DistanceSummary summary;
  int counted = 0;
  for (int v = 0; v < distances.size(); ++v) {
    if (!std::isfinite(distances(v))) continue;
    summary.mean += distances(v);
    summary.max = std::max(summary.max, distances(v));
    ++counted;
  }
  if (counted > 0) summary.mean /= counted;
  return summary;
}

double ShapeComparison::meanDistance() const {
  if (mean.empty()) return 0;
  double total = 0;
  for (const double m : mean) total += m;
  return total / static_cast<double>(mean.size());
}

double ShapeComparison::maxDistance() const { return max.empty() ? 0 : *std::max_element(max.begin(), max.end()); }

ShapeComparison compareDatasets(const data::Dataset& a, const data::Dataset& b, int size) {
  PIXELCLOTH_CHECK(a.poses.cols() == b.poses.cols(), "compare: the datasets' poses have "
                                                         << a.poses.cols() << " and " << b.poses.cols()
                                                         << " numbers: not the same garment's poses");
  const garment::Garment ga = data::datasetGarment(a.info), gb = data::datasetGarment(b.info);
  const bool same = sameMesh(ga, gb);
  const PatternMap map = same ? PatternMap{} : patternMap(ga, gb, size);
  ShapeComparison result;
  result.rowsA = static_cast<int>(a.poses.rows());
  result.rowsB = static_cast<int>(b.poses.rows());
  // Pose vectors as keys: the same seed draws bit-identical poses. Rows that share a pose pair up in order.
  std::map<std::vector<float>, std::vector<int>> rowsOfPose;
  for (int r = result.rowsA - 1; r >= 0; --r) {
    const Eigen::VectorXf p = a.poses.row(r).transpose();
    rowsOfPose[std::vector<float>(p.data(), p.data() + p.size())].push_back(r);
  }
  for (int r = 0; r < result.rowsB; ++r) {
    const Eigen::VectorXf p = b.poses.row(r).transpose();
    const auto found = rowsOfPose.find(std::vector<float>(p.data(), p.data() + p.size()));
    if (found == rowsOfPose.end() || found->second.empty()) continue;
    const int rowA = found->second.back();
    found->second.pop_back();
    const Eigen::MatrixX3d xa = a.positionsOf(rowA).cast<double>(), xb = b.positionsOf(r).cast<double>();
    const Eigen::VectorXd d = same ? vertexDistances(xa, xb) : sampledDistances(map, xa, xb);
    const DistanceSummary summary = summarise(d);
    result.rows.emplace_back(rowA, r);
    result.mean.push_back(summary.mean);
    result.max.push_back(summary.max);
  }
  return result;
}

}  // namespace pixelcloth::sim
