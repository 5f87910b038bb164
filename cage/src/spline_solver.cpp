// The length-preserving cage spline (issue 5): per-curve Ceres problems over the Hermite tangents, and the placement
// of every cage vertex at its rest arc-length fraction.
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
#include "pixelcloth/core/error.h"

namespace pixelcloth::cage {

const char* curveMethodName(CurveMethod method) {
  switch (method) {
    case CurveMethod::Linear:
      return "linear";
    case CurveMethod::CatmullRom:
      return "catmull_rom";
    case CurveMethod::Spline:
      return "spline";
  }
  return "spline";
}

CurveMethod curveMethodFromName(const std::string& name, const std::string& context) {
  for (CurveMethod m : {CurveMethod::Linear, CurveMethod::CatmullRom, CurveMethod::Spline})
    if (name == curveMethodName(m)) return m;
  PIXELCLOTH_FAIL(context << ": unknown curve method '" << name << "'; expected linear, catmull_rom or spline");
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
        for (int c = 0; c < 3; ++c) prior->prior[c] = spline.tangents[k][c];
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
      spline.tangents = catmullRomTangents(markers, restLengths, closed);
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

struct CageSplineSolver::Impl {
  Cage cage;
  SplineOptions options;
  int numVertices = 0;
  std::vector<int> cageVertices;
  std::vector<std::vector<double>> arc;               ///< per curve: cumulative rest arc length per index
  std::vector<std::unordered_map<int, int>> indexOf;  ///< per curve: vertex -> index along the curve
  std::unique_ptr<GeodesicDistance> geodesic;         ///< RestLengths::Geodesic only
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
};

CageSplineSolver::CageSplineSolver(const core::Garment& garment, const Cage& cage,
                                   const Eigen::MatrixX3d& restPositions, const SplineOptions& options)
    : impl_(std::make_unique<Impl>()) {
  options.validate();
  impl_->cage = cage;
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
    impl_->geodesic = std::make_unique<GeodesicDistance>(restPositions, garment.mesh.F);
}

CageSplineSolver::~CageSplineSolver() = default;
CageSplineSolver::CageSplineSolver(CageSplineSolver&&) noexcept = default;

const std::vector<int>& CageSplineSolver::cageVertices() const { return impl_->cageVertices; }
const Cage& CageSplineSolver::cage() const { return impl_->cage; }
const SplineOptions& CageSplineSolver::options() const { return impl_->options; }

CageFit CageSplineSolver::solve(const MarkerSet& markers) const { return solve(markers, impl_->options.method); }

CageFit CageSplineSolver::solve(const MarkerSet& markers, CurveMethod method) const {
  SplineOptions options = impl_->options;
  options.method = method;
  const int V = impl_->numVertices;
  CageFit fit;
  fit.positions = Eigen::MatrixX3d::Zero(V, 3);
  Eigen::VectorXi count = Eigen::VectorXi::Zero(V);
  for (const Marker& m : markers.markers)
    PIXELCLOTH_CHECK(m.hasPosition() && m.vertex >= 0 && m.vertex < V,
                     "spline: marker '" << m.name << "' has no position or a vertex out of range");

  for (size_t c = 0; c < impl_->cage.curves.size(); ++c) {
    const CageCurve& curve = impl_->cage.curves[c];
    const std::vector<double>& s = impl_->arc[c];
    const int n = static_cast<int>(curve.vertices.size());
    // The markers on this curve, in curve order (one per vertex).
    std::map<int, Eigen::Vector3d> onCurve;
    for (const Marker& m : markers.markers) {
      auto it = impl_->indexOf[c].find(m.vertex);
      if (it != impl_->indexOf[c].end()) onCurve.emplace(it->second, m.position);
    }
    if (!curve.closed) {
      PIXELCLOTH_CHECK(onCurve.count(0) && onCurve.count(n - 1),
                       "markers: curve '" << curve.name << "' needs a marker at each of its ends (vertices "
                                          << curve.vertices.front() << " and " << curve.vertices.back() << ")");
    } else {
      PIXELCLOTH_CHECK(onCurve.size() >= 3, "markers: closed curve '" << curve.name << "' has " << onCurve.size()
                                                                      << " markers, at least 3 needed");
    }
    std::vector<int> index;
    std::vector<Eigen::Vector3d> points;
    for (const auto& [i, p] : onCurve) {
      index.push_back(i);
      points.push_back(p);
    }
    const int K = static_cast<int>(index.size());
    const int segments = curve.closed ? K : K - 1;
    // Rest arc length of curve index i measured from marker 0, unwrapped around a closed curve.
    auto arcFrom = [&](int i) { return i >= index[0] ? s[i] - s[index[0]] : s[n] - s[index[0]] + s[i]; };
    std::vector<double> rest(segments), knot(K + 1);
    for (int k = 0; k < K; ++k) knot[k] = arcFrom(index[k]);
    knot[K] = curve.closed ? s[n] : knot[K - 1];
    for (int k = 0; k < segments; ++k) {
      rest[k] = options.restLengths == RestLengths::Geodesic
                    ? impl_->geodesicLength(curve.vertices[index[k]], curve.vertices[index[(k + 1) % K]])
                    : knot[k + 1] - knot[k];
      rest[k] = std::max(rest[k], 1e-9);
    }
    CurveSpline spline = fitCurveSpline(points, rest, curve.closed, options, &fit.summary);

    // Every vertex of the curve at its rest arc-length fraction within its segment.
    int segment = 0;
    std::array<double, kArcTableSteps + 1> table{};
    int tableOf = -1;
    for (int step = 0; step < n; ++step) {
      const int i = (index[0] + step) % n;
      const double a = arcFrom(i);
      while (segment + 1 < segments && a > knot[segment + 1]) ++segment;
      const double span = knot[segment + 1] - knot[segment];
      const double fraction = span > 0 ? std::clamp((a - knot[segment]) / span, 0.0, 1.0) : 0.0;
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
