// The length-preserving cage spline (DESIGN.md, "Key-point-to-cage spline solver"): per-curve Ceres problems over the
// Hermite tangents, and the placement of every cage vertex at its rest arc-length fraction.
#include "pixelcloth/cage/spline_solver.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <unordered_map>

#include "pixelcloth/cage/spline_residuals.h"
#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::cage {

namespace {
const core::EnumNames<CurveMethod, 3> kCurveMethods{
    "curve method",
    {{{CurveMethod::Linear, "linear"}, {CurveMethod::CatmullRom, "catmull_rom"}, {CurveMethod::Spline, "spline"}}}};
}  // namespace

const char* curveMethodName(CurveMethod method) { return kCurveMethods.name(method); }

CurveMethod curveMethodFromName(const std::string& name, const std::string& context) {
  return kCurveMethods.fromName(name, context);
}

void SplineOptions::validate() const {
  PIXELCLOTH_CHECK(std::isfinite(lengthTolerance) && lengthTolerance > 0,
                   "spline: lengthTolerance " << lengthTolerance << ", expected > 0");
  PIXELCLOTH_CHECK(std::isfinite(bendingWeight) && bendingWeight >= 0,
                   "spline: bendingWeight " << bendingWeight << ", expected >= 0");
  PIXELCLOTH_CHECK(std::isfinite(markerSigma) && markerSigma >= 0,
                   "spline: markerSigma " << markerSigma << " m, expected >= 0");
  PIXELCLOTH_CHECK(std::isfinite(tangentPrior) && tangentPrior >= 0,
                   "spline: tangentPrior " << tangentPrior << ", expected >= 0");
  PIXELCLOTH_CHECK(maxIterations >= 1, "spline: maxIterations " << maxIterations << ", expected >= 1");
}

std::string SplineSummary::summary() const {
  std::ostringstream s;
  s << curves << " curves, " << iterations << " iterations, cost " << std::setprecision(3) << initialCost << " -> "
    << finalCost << ", max segment length error " << std::setprecision(2) << 100 * maxLengthError << "%";
  return s.str();
}

// ---------------------------------------------------------------------------------------------------------------------
// CurveSpline

Eigen::Vector3d CurveSpline::position(int segment, double t) const {
  const int k = segment, j = (segment + 1) % static_cast<int>(points.size());
  if (linear) return (1 - t) * points[k] + t * points[j];
  const double L = restLengths[k], t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * points[k] + (t3 - 2 * t2 + t) * L * tangents[k] + (-2 * t3 + 3 * t2) * points[j] +
         (t3 - t2) * L * tangents[j];
}

double CurveSpline::arcLength(int segment) const {
  const int k = segment, j = (segment + 1) % static_cast<int>(points.size());
  if (linear) return (points[j] - points[k]).norm();
  return hermiteArcLength(points[k].data(), tangents[k].data(), points[j].data(), tangents[j].data(), restLengths[k]);
}

double CurveSpline::arcLength() const {
  double sum = 0;
  for (int k = 0; k < numSegments(); ++k) sum += arcLength(k);
  return sum;
}

namespace {
constexpr int kArcTableSteps = 16;

/// Cumulative arc length of a segment at t = i / kArcTableSteps.
std::array<double, kArcTableSteps + 1> arcTable(const CurveSpline& spline, int segment) {
  std::array<double, kArcTableSteps + 1> table{};
  const int k = segment, j = (segment + 1) % static_cast<int>(spline.points.size());
  const double L = spline.restLengths[k];
  for (int i = 0; i < kArcTableSteps; ++i) {
    double piece = 0;
    for (int g = 0; g < GaussLegendre5::kPoints; ++g) {
      const double t = (i + GaussLegendre5::kNodes[g]) / kArcTableSteps;
      double v[3];
      detail::hermiteVelocity(spline.points[k].data(), spline.tangents[k].data(), spline.points[j].data(),
                              spline.tangents[j].data(), L, t, v);
      piece += GaussLegendre5::kWeights[g] * std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    table[i + 1] = table[i] + piece / kArcTableSteps;
  }
  return table;
}

/// Parameter t at `fraction` of the arc length tabulated in `table`.
double parameterAt(const std::array<double, kArcTableSteps + 1>& table, double fraction) {
  const double target = std::clamp(fraction, 0.0, 1.0) * table.back();
  int i = 0;
  while (i + 1 < kArcTableSteps && table[i + 1] < target) ++i;
  const double span = table[i + 1] - table[i];
  const double local = span > 0 ? std::clamp((target - table[i]) / span, 0.0, 1.0) : 0.0;
  return (i + local) / kArcTableSteps;
}
}  // namespace

Eigen::Vector3d CurveSpline::atArcFraction(int segment, double fraction) const {
  if (linear) return position(segment, std::clamp(fraction, 0.0, 1.0));
  return position(segment, parameterAt(arcTable(*this, segment), fraction));
}

// ---------------------------------------------------------------------------------------------------------------------
// Fitting one curve

namespace {

/// The Catmull-Rom tangents (derivatives in rest arc length) of markers `p` with segment rest lengths `L`.
std::vector<Eigen::Vector3d> catmullRomTangents(const std::vector<Eigen::Vector3d>& p, const std::vector<double>& L,
                                                bool closed) {
  const int K = static_cast<int>(p.size());
  std::vector<Eigen::Vector3d> d(K);
  for (int k = 0; k < K; ++k) {
    if (closed) {
      const int prev = (k + K - 1) % K, next = (k + 1) % K;
      d[k] = (p[next] - p[prev]) / (L[prev] + L[k]);
    } else if (k > 0 && k < K - 1) {
      d[k] = (p[k + 1] - p[k - 1]) / (L[k - 1] + L[k]);
    }
  }
  if (!closed) {
    if (K == 2) {
      d[0] = d[1] = (p[1] - p[0]) / L[0];
    } else {
      // The parabola through the first (last) three markers: its end derivative is 2 chord / L - the next one.
      d[0] = 2 * (p[1] - p[0]) / L[0] - d[1];
      d[K - 1] = 2 * (p[K - 1] - p[K - 2]) / L[K - 2] - d[K - 2];
    }
  }
  return d;
}

}  // namespace

CurveSpline fitCurveSpline(const std::vector<Eigen::Vector3d>& markers, const std::vector<double>& restLengths,
                           bool closed, const SplineOptions& options, SplineSummary* summary) {
  options.validate();
  const int K = static_cast<int>(markers.size());
  PIXELCLOTH_CHECK(K >= (closed ? 3 : 2), "spline: " << K << " markers, a " << (closed ? "closed" : "open")
                                                     << " curve needs at least " << (closed ? 3 : 2));
  const int segments = closed ? K : K - 1;
  PIXELCLOTH_CHECK(static_cast<int>(restLengths.size()) == segments,
                   "spline: " << restLengths.size() << " rest lengths for " << segments << " segments");
  for (int k = 0; k < K; ++k) PIXELCLOTH_CHECK(markers[k].allFinite(), "spline: marker " << k << " is not finite");
  for (int k = 0; k < segments; ++k)
    PIXELCLOTH_CHECK(std::isfinite(restLengths[k]) && restLengths[k] > 0,
                     "spline: rest length " << k << " is " << restLengths[k] << ", expected > 0");

  CurveSpline spline;
  spline.closed = closed;
  spline.points = markers;
  spline.restLengths = restLengths;
  spline.linear = options.method == CurveMethod::Linear;
  spline.tangents = catmullRomTangents(markers, restLengths, closed);
  const std::vector<Eigen::Vector3d> start = spline.tangents;
  if (summary) ++summary->curves;

  if (options.method == CurveMethod::Spline) {
    ceres::Problem problem;
    std::vector<double*> p(K), d(K);
    for (int k = 0; k < K; ++k) {
      p[k] = spline.points[k].data();
      d[k] = spline.tangents[k].data();
    }
    for (int k = 0; k < segments; ++k) {
      const int j = (k + 1) % K;
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SegmentLengthResidual, 1, 3, 3, 3, 3>(
                                   new SegmentLengthResidual{restLengths[k], options.lengthTolerance, options.stretch}),
                               nullptr, p[k], d[k], p[j], d[j]);
      if (options.bendingWeight > 0)
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<BendingResidual, BendingResidual::kResiduals, 3, 3, 3, 3>(
                new BendingResidual{restLengths[k], options.bendingWeight}),
            nullptr, p[k], d[k], p[j], d[j]);
    }
    for (int k = 0; k < K; ++k) {
      if (options.tangentPrior > 0) {
        auto* prior = new TangentPriorResidual;
        for (int c = 0; c < 3; ++c) prior->prior[c] = start[k][c];
        prior->weight = options.tangentPrior;
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<TangentPriorResidual, 3, 3>(prior), nullptr, d[k]);
      }
      if (options.markerSigma > 0) {
        auto* fit = new MarkerFitResidual;
        for (int c = 0; c < 3; ++c) fit->observed[c] = markers[k][c];
        fit->sigma = options.markerSigma;
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<MarkerFitResidual, 3, 3>(fit), nullptr, p[k]);
      } else {
        problem.SetParameterBlockConstant(p[k]);
      }
    }
    ceres::Solver::Options solverOptions;
    solverOptions.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    solverOptions.max_num_iterations = options.maxIterations;
    solverOptions.logging_type = ceres::SILENT;
    solverOptions.minimizer_progress_to_stdout = false;
    solverOptions.num_threads = 1;
    solverOptions.function_tolerance = 1e-6;
    solverOptions.parameter_tolerance = 1e-10;
    ceres::Solver::Summary result;
    ceres::Solve(solverOptions, &problem, &result);
    if (summary) {
      summary->iterations += static_cast<int>(result.iterations.size());
      summary->initialCost += result.initial_cost;
      summary->finalCost += result.final_cost;
    }
    // A solve that went astray (not finite) falls back to the Catmull-Rom start.
    bool finite = true;
    for (int k = 0; k < K; ++k) finite = finite && spline.points[k].allFinite() && spline.tangents[k].allFinite();
    if (!finite) {
      spline.points = markers;
      spline.tangents = start;
    }
  }
  if (summary) {
    for (int k = 0; k < segments; ++k) {
      // With stretch allowed only a shortfall is an error.
      const double excess = spline.arcLength(k) - restLengths[k];
      const double error =
          options.stretch && options.method == CurveMethod::Spline ? std::max(0.0, -excess) : std::abs(excess);
      summary->maxLengthError = std::max(summary->maxLengthError, error / restLengths[k]);
    }
  }
  return spline;
}

// ---------------------------------------------------------------------------------------------------------------------
// The cage solver

namespace {
/// The markers of one curve in one frame.
struct CurveMarkers {
  std::vector<int> index;               ///< position along the curve of each marker, ascending
  std::vector<Eigen::Vector3d> points;  ///< their positions
  std::vector<double> knot;  ///< rest arc length of each marker from the first; one more entry: the loop's length
                             ///< (closed) or the last marker's again (open)
  std::vector<double> rest;  ///< rest length of each segment
};

/// Length of `curve` from its vertex index `from` to `to` (wrapping round a closed curve) through `positions`, after
/// `passes` passes of the [1/4, 1/2, 1/4] filter over the vertices between them (both ends held).
double smoothedSegmentLength(const Eigen::MatrixX3d& positions, const CageCurve& curve, int from, int to, int passes) {
  const int n = static_cast<int>(curve.vertices.size());
  std::vector<Eigen::Vector3d> x;
  for (int i = from;; i = (i + 1) % n) {
    x.push_back(positions.row(curve.vertices[i]).transpose());
    if (i == to) break;
  }
  std::vector<Eigen::Vector3d> next = x;
  for (int pass = 0; pass < passes; ++pass) {
    for (size_t i = 1; i + 1 < x.size(); ++i) next[i] = 0.5 * x[i] + 0.25 * (x[i - 1] + x[i + 1]);
    std::swap(x, next);
  }
  double length = 0;
  for (size_t i = 0; i + 1 < x.size(); ++i) length += (x[i + 1] - x[i]).norm();
  return length;
}
}  // namespace

struct CageSplineSolver::Impl {
  Cage cage;
  std::string garmentName;
  SplineOptions options;
  std::optional<LengthModel> lengthModel;
  int numVertices = 0;
  std::vector<int> cageVertices;
  std::vector<std::vector<double>> arc;               ///< per curve: cumulative rest arc length per index
  std::vector<std::unordered_map<int, int>> indexOf;  ///< per curve: vertex -> index along the curve
  std::unique_ptr<core::GeodesicDistance> geodesic;   ///< RestLengths::Geodesic only
  mutable std::mutex geodesicMutex;
  mutable std::map<std::pair<int, int>, double> geodesicCache;

  double geodesicLength(int a, int b) const {
    const auto key = std::minmax(a, b);
    std::lock_guard<std::mutex> lock(geodesicMutex);
    auto it = geodesicCache.find(key);
    if (it != geodesicCache.end()) return it->second;
    const double d = geodesic->between(key.first, key.second);
    geodesicCache[key] = d;
    return d;
  }

  /// The markers of curve `c` (positions from `positions` when given, else from the markers), with the checks that
  /// each curve has what its spline needs.
  CurveMarkers collect(int c, const MarkerSet& markers, const Eigen::MatrixX3d* positions = nullptr) const {
    const CageCurve& curve = cage.curves[c];
    const std::vector<double>& s = arc[c];
    const int n = static_cast<int>(curve.vertices.size());
    std::map<int, Eigen::Vector3d> onCurve;
    for (const Marker& m : markers.markers) {
      auto it = indexOf[c].find(m.vertex);
      if (it != indexOf[c].end())
        onCurve.emplace(it->second, positions ? Eigen::Vector3d(positions->row(m.vertex)) : m.position);
    }
    if (!curve.closed) {
      PIXELCLOTH_CHECK(onCurve.count(0) && onCurve.count(n - 1),
                       "markers: curve '" << curve.name << "' needs a marker at each of its ends (vertices "
                                          << curve.vertices.front() << " and " << curve.vertices.back() << ")");
    } else {
      PIXELCLOTH_CHECK(onCurve.size() >= 3, "markers: closed curve '" << curve.name << "' has " << onCurve.size()
                                                                      << " markers, at least 3 needed");
    }
    CurveMarkers out;
    for (const auto& [i, p] : onCurve) {
      out.index.push_back(i);
      out.points.push_back(p);
    }
    const int K = static_cast<int>(out.index.size());
    const int segments = curve.closed ? K : K - 1;
    out.knot.resize(K + 1);
    for (int k = 0; k < K; ++k) out.knot[k] = arcFrom(c, out.index[0], out.index[k]);
    out.knot[K] = curve.closed ? s[n] : out.knot[K - 1];
    out.rest.resize(segments);
    for (int k = 0; k < segments; ++k) {
      out.rest[k] = options.restLengths == RestLengths::Geodesic
                        ? geodesicLength(curve.vertices[out.index[k]], curve.vertices[out.index[(k + 1) % K]])
                        : out.knot[k + 1] - out.knot[k];
      out.rest[k] = std::max(out.rest[k], 1e-9);
    }
    return out;
  }

  /// Rest arc length of curve index i measured from index `first`, unwrapped around a closed curve.
  double arcFrom(int c, int first, int i) const {
    const std::vector<double>& s = arc[c];
    return i >= first ? s[i] - s[first] : s.back() - s[first] + s[i];
  }
};

CageSplineSolver::CageSplineSolver(const garment::Garment& garment, const Cage& cage,
                                   const Eigen::MatrixX3d& restPositions, const SplineOptions& options)
    : impl_(std::make_unique<Impl>()) {
  options.validate();
  impl_->cage = cage;
  impl_->garmentName = garment.name;
  impl_->options = options;
  impl_->numVertices = garment.mesh.numVertices();
  const bool needs3d = options.restLengths != RestLengths::Pattern;
  PIXELCLOTH_CHECK(!needs3d || restPositions.rows() == impl_->numVertices,
                   "spline: " << restLengthsName(options.restLengths) << " rest lengths need the rest garment's "
                              << impl_->numVertices << " positions, got " << restPositions.rows());
  std::vector<bool> onCage(impl_->numVertices, false);
  for (const CageCurve& curve : cage.curves) {
    impl_->arc.push_back(needs3d ? polylineArcLengths(restPositions, curve) : patternArcLengths(garment, curve));
    std::unordered_map<int, int> index;
    for (size_t i = 0; i < curve.vertices.size(); ++i) {
      index[curve.vertices[i]] = static_cast<int>(i);
      onCage.at(curve.vertices[i]) = true;
    }
    impl_->indexOf.push_back(std::move(index));
  }
  for (int v = 0; v < impl_->numVertices; ++v)
    if (onCage[v]) impl_->cageVertices.push_back(v);
  if (options.restLengths == RestLengths::Geodesic)
    impl_->geodesic = std::make_unique<core::GeodesicDistance>(restPositions, garment.mesh.F);
}

CageSplineSolver::~CageSplineSolver() = default;
CageSplineSolver::CageSplineSolver(CageSplineSolver&&) noexcept = default;

const std::vector<int>& CageSplineSolver::cageVertices() const { return impl_->cageVertices; }
const Cage& CageSplineSolver::cage() const { return impl_->cage; }
const SplineOptions& CageSplineSolver::options() const { return impl_->options; }
const std::optional<LengthModel>& CageSplineSolver::lengthModel() const { return impl_->lengthModel; }

void CageSplineSolver::setLengthModel(std::optional<LengthModel> model, const std::string& context) {
  if (model) model->validate(impl_->garmentName, impl_->cage, context);
  impl_->lengthModel = std::move(model);
}

LengthModel CageSplineSolver::fitLengthModel(const MarkerSet& definition, const std::vector<Eigen::MatrixX3d>& samples,
                                             double markerSpacing, const LengthModelOptions& options) const {
  options.validate();
  PIXELCLOTH_CHECK(!samples.empty(), "length model: no training garments to fit on");
  const int C = static_cast<int>(impl_->cage.curves.size());
  // Per curve: (chord / rest, smoothed length / rest) of every training segment.
  std::vector<std::vector<Eigen::Vector2d>> points(C);
  for (size_t i = 0; i < samples.size(); ++i) {
    PIXELCLOTH_CHECK(samples[i].rows() == impl_->numVertices && samples[i].allFinite(),
                     "length model: training garment " << i << " has " << samples[i].rows() << " rows, expected "
                                                       << impl_->numVertices << " finite positions");
    for (int c = 0; c < C; ++c) {
      const CurveMarkers m = impl_->collect(c, definition, &samples[i]);
      const int K = static_cast<int>(m.index.size());
      for (int k = 0; k < static_cast<int>(m.rest.size()); ++k) {
        const double chord = (m.points[(k + 1) % K] - m.points[k]).norm();
        const double worn = smoothedSegmentLength(samples[i], impl_->cage.curves[c], m.index[k], m.index[(k + 1) % K],
                                                  options.smoothingPasses);
        points[c].emplace_back(chord / m.rest[k], worn / m.rest[k]);
      }
    }
  }
  // Least squares of ratio = a + b x: normal equations, optionally pulled towards a prior line with weight w.
  auto fitLine = [](const std::vector<Eigen::Vector2d>& xy, const Eigen::Vector2d& prior, double w) {
    Eigen::Matrix2d A = w * Eigen::Matrix2d::Identity();
    Eigen::Vector2d rhs = w * prior;
    for (const Eigen::Vector2d& p : xy) {
      const Eigen::Vector2d row(1, p.x());
      A += row * row.transpose();
      rhs += row * p.y();
    }
    return Eigen::Vector2d(A.ldlt().solve(rhs));
  };
  std::vector<Eigen::Vector2d> pooled;
  for (const auto& list : points) pooled.insert(pooled.end(), list.begin(), list.end());
  // The pooled line gets a whisper of the length-preserving prior (1, 0) so that it is defined even when every chord
  // is the same.
  const Eigen::Vector2d all = fitLine(pooled, Eigen::Vector2d(1, 0), 1e-6);
  LengthModel model;
  model.garment = impl_->garmentName;
  model.markerSpacing = markerSpacing;
  model.smoothingPasses = options.smoothingPasses;
  model.samples = static_cast<int>(samples.size());
  for (int c = 0; c < C; ++c) {
    const Eigen::Vector2d line = fitLine(points[c], all, options.shrinkage);
    double squared = 0;
    for (const Eigen::Vector2d& p : points[c]) squared += std::pow(line[0] + line[1] * p.x() - p.y(), 2);
    model.curves[impl_->cage.curves[c].name] = {line[0], line[1], static_cast<int>(points[c].size()),
                                                std::sqrt(squared / std::max<size_t>(1, points[c].size()))};
  }
  return model;
}

CageFit CageSplineSolver::solve(const MarkerSet& markers) const { return solve(markers, impl_->options.method); }

CageFit CageSplineSolver::solve(const MarkerSet& markers, CurveMethod method) const {
  SplineOptions options = impl_->options;
  options.method = method;
  const int V = impl_->numVertices;
  const int C = static_cast<int>(impl_->cage.curves.size());
  CageFit fit;
  fit.positions = Eigen::MatrixX3d::Zero(V, 3);
  Eigen::VectorXi count = Eigen::VectorXi::Zero(V);
  for (const Marker& m : markers.markers)
    PIXELCLOTH_CHECK(m.hasPosition() && m.vertex >= 0 && m.vertex < V,
                     "spline: marker '" << m.name << "' has no position or a vertex out of range");

  std::vector<CurveMarkers> all(C);
  std::vector<std::vector<double>> lengths(C);  // what each segment's length term aims at
  const bool learned = impl_->lengthModel && method == CurveMethod::Spline;
  for (int c = 0; c < C; ++c) {
    all[c] = impl_->collect(c, markers);
    lengths[c] = all[c].rest;
    if (learned) {
      const int K = static_cast<int>(all[c].points.size());
      for (size_t k = 0; k < lengths[c].size(); ++k)
        lengths[c][k] = impl_->lengthModel->target(impl_->cage.curves[c].name, all[c].rest[k],
                                                   (all[c].points[(k + 1) % K] - all[c].points[k]).norm());
    }
  }
  // The learned lengths are the worn ones, to be met both ways; rest lengths are lower bounds when cloth may stretch.
  if (learned) options.stretch = false;

  for (int c = 0; c < C; ++c) {
    const CageCurve& curve = impl_->cage.curves[c];
    const CurveMarkers& m = all[c];
    const int n = static_cast<int>(curve.vertices.size());
    const int K = static_cast<int>(m.index.size());
    const int segments = curve.closed ? K : K - 1;
    CurveSpline spline = fitCurveSpline(m.points, lengths[c], curve.closed, options, &fit.summary);

    // Every vertex of the curve at its rest arc-length fraction within its segment.
    int segment = 0;
    std::array<double, kArcTableSteps + 1> table{};
    int tableOf = -1;
    for (int step = 0; step < n; ++step) {
      const int i = (m.index[0] + step) % n;
      const double a = impl_->arcFrom(c, m.index[0], i);
      while (segment + 1 < segments && a > m.knot[segment + 1]) ++segment;
      const double span = m.knot[segment + 1] - m.knot[segment];
      const double fraction = span > 0 ? std::clamp((a - m.knot[segment]) / span, 0.0, 1.0) : 0.0;
      Eigen::Vector3d x;
      if (spline.linear) {
        x = spline.position(segment, fraction);
      } else {
        if (tableOf != segment) {
          table = arcTable(spline, segment);
          tableOf = segment;
        }
        x = spline.position(segment, parameterAt(table, fraction));
      }
      fit.positions.row(curve.vertices[i]) += x.transpose();
      ++count[curve.vertices[i]];
    }
    fit.curves.push_back(std::move(spline));
  }
  for (int v = 0; v < V; ++v) {
    if (count[v] > 0)
      fit.positions.row(v) /= count[v];
    else
      fit.positions.row(v).setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return fit;
}

double curvePolylineLength(const Eigen::Ref<const Eigen::MatrixX3d>& positions, const CageCurve& curve) {
  return polylineArcLengths(positions, curve).back();
}

}  // namespace pixelcloth::cage
