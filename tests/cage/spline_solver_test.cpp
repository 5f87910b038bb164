// The length-preserving cage spline: passes through its markers, recovers sampled circles and helices, residuals match
// numeric differentiation, closed loops close smoothly, noisy markers are survived; on the T-shirt's cage it places
// every cage vertex.
#include "pixelcloth/cage/spline_solver.h"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/cage/spline_residuals.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace pcg = pixelcloth::cage;

namespace {

/// K points on a helix of radius r and pitch c per radian (c = 0: a circle), over `turns` of 2 pi, and the true arc
/// lengths between consecutive points (closed: also back to the first, for a circle).
struct Sampled {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> lengths;
  double total = 0;
};
Sampled helix(int K, double r, double c, double turns, bool closed) {
  Sampled s;
  const double span = 2 * M_PI * turns, step = span / (closed ? K : K - 1);
  for (int k = 0; k < K; ++k) {
    const double a = k * step;
    s.points.emplace_back(r * std::cos(a), r * std::sin(a), c * a);
  }
  const int segments = closed ? K : K - 1;
  for (int k = 0; k < segments; ++k) s.lengths.push_back(step * std::sqrt(r * r + c * c));
  s.total = segments * s.lengths.front();
  return s;
}

}  // namespace

TEST(SplineSolver, PassesThroughItsMarkers) {
  const Sampled s = helix(7, 0.2, 0.03, 0.8, false);
  for (pcg::CurveMethod method : {pcg::CurveMethod::Linear, pcg::CurveMethod::CatmullRom, pcg::CurveMethod::Spline}) {
    pcg::SplineOptions options;
    options.method = method;
    const pcg::CurveSpline spline = pcg::fitCurveSpline(s.points, s.lengths, false, options);
    for (int k = 0; k < spline.numSegments(); ++k) {
      EXPECT_LT((spline.position(k, 0) - s.points[k]).norm(), 1e-12) << pcg::curveMethodName(method);
      EXPECT_LT((spline.position(k, 1) - s.points[k + 1]).norm(), 1e-12) << pcg::curveMethodName(method);
      EXPECT_LT((spline.atArcFraction(k, 0) - s.points[k]).norm(), 1e-12);
      EXPECT_LT((spline.atArcFraction(k, 1) - s.points[k + 1]).norm(), 1e-9);
    }
  }
}

TEST(SplineSolver, RecoversSparseCircleAndHelixWithinOnePercentOfArcLength) {
  struct Case {
    const char* name;
    Sampled s;
    bool closed;
  };
  // Six markers on a circle (60 degrees apart) and seven on one and a half turns of a helix (90 degrees apart).
  const Case cases[] = {{"circle", helix(6, 0.15, 0, 1, true), true},
                        {"helix", helix(7, 0.1, 0.04, 1.5, false), false}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    // The length-preserving solver itself: no pull towards the Catmull-Rom tangents (the garment default, which gives
    // up some length for the Catmull-Rom shape, is checked below to move towards the length).
    pcg::SplineOptions options;
    options.tangentPrior = 0;
    const pcg::CurveSpline spline = pcg::fitCurveSpline(c.s.points, c.s.lengths, c.closed, options);
    EXPECT_NEAR(spline.arcLength(), c.s.total, 0.01 * c.s.total);
    for (int k = 0; k < spline.numSegments(); ++k)
      EXPECT_NEAR(spline.arcLength(k), c.s.lengths[k], 0.01 * c.s.lengths[k]) << "segment " << k;
    // Linear is too short by more than that: the test can tell.
    options.method = pcg::CurveMethod::Linear;
    EXPECT_LT(pcg::fitCurveSpline(c.s.points, c.s.lengths, c.closed, options).arcLength(), 0.98 * c.s.total);
    // The default options land between Catmull-Rom and the true length.
    options.method = pcg::CurveMethod::CatmullRom;
    const double catmullRom = pcg::fitCurveSpline(c.s.points, c.s.lengths, c.closed, options).arcLength();
    const double byDefault = pcg::fitCurveSpline(c.s.points, c.s.lengths, c.closed).arcLength();
    EXPECT_GT(byDefault, catmullRom);
    EXPECT_LT(byDefault, c.s.total * 1.001);
  }
  // The recovered circle stays near the circle between the markers.
  const Sampled circle = helix(6, 0.15, 0, 1, true);
  pcg::SplineOptions exact;
  exact.tangentPrior = 0;
  const pcg::CurveSpline spline = pcg::fitCurveSpline(circle.points, circle.lengths, true, exact);
  for (int k = 0; k < 6; ++k)
    for (double t : {0.25, 0.5, 0.75}) {
      const Eigen::Vector3d p = spline.position(k, t);
      EXPECT_NEAR(p.head<2>().norm(), 0.15, 0.003) << k << " " << t;
      EXPECT_NEAR(p.z(), 0, 1e-9);
    }
}

TEST(SplineSolver, ClosedLoopHasNoKinkWhereItCloses) {
  const Sampled s = helix(5, 0.12, 0, 1, true);
  const pcg::CurveSpline spline = pcg::fitCurveSpline(s.points, s.lengths, true);
  // Derivative with respect to rest arc length on both sides of every marker, the closing one (0) included.
  const int K = 5;
  for (int k = 0; k < K; ++k) {
    const int before = (k + K - 1) % K;
    const double h = 1e-6;
    const Eigen::Vector3d in = (spline.position(before, 1) - spline.position(before, 1 - h)) / (h * s.lengths[before]);
    const Eigen::Vector3d out = (spline.position(k, h) - spline.position(k, 0)) / (h * s.lengths[k]);
    EXPECT_LT((in - out).norm(), 1e-4 * out.norm()) << "marker " << k;
  }
}

TEST(SplineSolver, NoisyMarkersDoNotMakeTheSolveFail) {
  std::mt19937_64 random(3);
  std::normal_distribution<double> noise(0, 0.005);
  Sampled s = helix(9, 0.15, 0.02, 1, false);
  for (auto& p : s.points) p += Eigen::Vector3d(noise(random), noise(random), noise(random));
  // Two markers on top of each other, and a short segment that the noise makes impossible to keep at its length.
  s.points[4] = s.points[3] + Eigen::Vector3d(1e-7, 0, 0);
  for (double sigma : {0.0, 0.005}) {
    pcg::SplineOptions options;
    options.markerSigma = sigma;
    pcg::SplineSummary summary;
    const pcg::CurveSpline spline = pcg::fitCurveSpline(s.points, s.lengths, false, options, &summary);
    for (int k = 0; k < spline.numSegments(); ++k)
      for (double t : {0.0, 0.3, 0.7, 1.0}) EXPECT_TRUE(spline.position(k, t).allFinite()) << sigma;
    EXPECT_TRUE(std::isfinite(spline.arcLength()));
    EXPECT_LE(summary.finalCost, summary.initialCost) << summary.summary();
    if (sigma > 0) {
      for (int k = 0; k < 9; ++k) EXPECT_LT((spline.points[k] - s.points[k]).norm(), 0.05);
    }
  }
}

TEST(SplineSolver, RefusesTooFewMarkersAndBadLengths) {
  const Sampled s = helix(3, 0.1, 0, 1, true);
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] {
              pcg::fitCurveSpline({s.points[0], s.points[1]}, {0.1, 0.1}, true);
            }).find("at least 3"),
            std::string::npos);
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] {
              pcg::fitCurveSpline({s.points[0], s.points[1]}, {-1}, false);
            }).find("rest length"),
            std::string::npos);
  pcg::SplineOptions bad;
  bad.lengthTolerance = 0;
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] { bad.validate(); }).find("lengthTolerance"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------------------------------
// Each functor against numeric differentiation

namespace {

/// Compares the Jacobians of an autodiff cost function with central differences of the same functor.
template <typename Functor, int R, int... Blocks>
void expectAutodiffMatchesNumeric(const Functor& functor, std::vector<std::vector<double>> parameters) {
  ceres::AutoDiffCostFunction<Functor, R, Blocks...> autodiff(new Functor(functor));
  ceres::NumericDiffCostFunction<Functor, ceres::CENTRAL, R, Blocks...> numeric(new Functor(functor));
  std::vector<double*> blocks;
  for (auto& p : parameters) blocks.push_back(p.data());
  const int sizes[] = {Blocks...};
  const int n = sizeof...(Blocks);
  std::vector<std::vector<double>> ja(n), jn(n);
  std::vector<double*> pa(n), pn(n);
  for (int b = 0; b < n; ++b) {
    ja[b].resize(R * sizes[b]);
    jn[b].resize(R * sizes[b]);
    pa[b] = ja[b].data();
    pn[b] = jn[b].data();
  }
  std::vector<double> ra(R), rn(R);
  ASSERT_TRUE(autodiff.Evaluate(blocks.data(), ra.data(), pa.data()));
  ASSERT_TRUE(numeric.Evaluate(blocks.data(), rn.data(), pn.data()));
  double scale = 1e-12;
  for (int b = 0; b < n; ++b)
    for (double v : ja[b]) scale = std::max(scale, std::abs(v));
  for (int r = 0; r < R; ++r) EXPECT_NEAR(ra[r], rn[r], 1e-12 * (1 + std::abs(ra[r])));
  for (int b = 0; b < n; ++b)
    for (size_t i = 0; i < ja[b].size(); ++i)
      EXPECT_NEAR(ja[b][i], jn[b][i], 1e-6 * scale) << "block " << b << " entry " << i;
}

}  // namespace

TEST(SplineResiduals, EachMatchesNumericDifferentiation) {
  const std::vector<std::vector<double>> segment = {
      {0.1, 1.2, -0.05}, {0.8, 0.3, -0.4}, {0.22, 1.25, 0.02}, {0.6, -0.2, 0.7}};
  expectAutodiffMatchesNumeric<pcg::SegmentLengthResidual, 1, 3, 3, 3, 3>(pcg::SegmentLengthResidual{0.13, 0.01},
                                                                          segment);
  expectAutodiffMatchesNumeric<pcg::BendingResidual, pcg::BendingResidual::kResiduals, 3, 3, 3, 3>(
      pcg::BendingResidual{0.13, 0.3}, segment);
  pcg::MarkerFitResidual fit;
  fit.observed[0] = 0.1;
  fit.observed[1] = 1.1;
  fit.observed[2] = 0.0;
  fit.sigma = 0.004;
  expectAutodiffMatchesNumeric<pcg::MarkerFitResidual, 3, 3>(fit, {{0.11, 1.09, 0.003}});
}

TEST(SplineResiduals, BendingIsTheExactIntegralOfTheSquaredSecondDerivative) {
  // A reference integral by a fine midpoint rule against the 2-point Gauss-Legendre residuals.
  const double p0[3] = {0.1, 1.2, -0.05}, d0[3] = {0.8, 0.3, -0.4}, p1[3] = {0.22, 1.25, 0.02},
               d1[3] = {0.6, -0.2, 0.7};
  const double L = 0.13;
  double reference = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    double a[3];
    pcg::detail::hermiteAcceleration(p0, d0, p1, d1, L, (i + 0.5) / n, a);
    reference += (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) / (L * L) / n;
  }
  double r[pcg::BendingResidual::kResiduals];
  pcg::BendingResidual{L, 1.0}(p0, d0, p1, d1, r);
  double sum = 0;
  for (double v : r) sum += v * v;
  EXPECT_NEAR(sum, reference, 1e-6 * reference);
}

TEST(SplineResiduals, ArcLengthOfAStraightSegmentIsItsChord) {
  const double p0[3] = {0, 0, 0}, p1[3] = {0.3, 0.4, 0}, d[3] = {0.6, 0.8, 0};
  EXPECT_NEAR(pcg::hermiteArcLength(p0, d, p1, d, 0.5), 0.5, 1e-12);
}

// ---------------------------------------------------------------------------------------------------------------------
// On the T-shirt's cage

TEST(CageSplineSolver, PlacesEveryCageVertexAndHitsTheMarkers) {
  const auto& shirt = pixelcloth::testing::tshirt();
  const pcg::Cage cage = pcg::garmentCage(shirt);
  const pcg::MarkerSet definition = pcg::defineMarkers(shirt, cage);
  // A smooth deformation of the rest shirt as ground truth.
  Eigen::MatrixX3d truth = shirt.mesh.V;
  for (int v = 0; v < truth.rows(); ++v) {
    const Eigen::Vector3d x = shirt.mesh.V.row(v);
    truth.row(v) += Eigen::RowVector3d(0.02 * std::sin(4 * x.y()), 0.01 * std::cos(3 * x.x()), 0.03 * x.x() * x.x());
  }
  const pcg::MarkerSet markers = pcg::placeMarkers(definition, truth);
  for (pcg::CurveMethod method : {pcg::CurveMethod::Linear, pcg::CurveMethod::CatmullRom, pcg::CurveMethod::Spline}) {
    SCOPED_TRACE(pcg::curveMethodName(method));
    // Rest lengths from the rest shirt in 3D, which the mild deformation nearly keeps (its pattern lengths differ).
    pcg::SplineOptions options;
    options.restLengths = pcg::RestLengths::Polyline;
    const pcg::CageSplineSolver solver(shirt, cage, shirt.mesh.V, options);
    const pcg::CageFit fit = solver.solve(markers, method);
    ASSERT_EQ(fit.positions.rows(), shirt.mesh.numVertices());
    ASSERT_EQ(fit.curves.size(), cage.curves.size());
    for (int v : solver.cageVertices()) EXPECT_TRUE(fit.positions.row(v).allFinite()) << v;
    for (const pcg::Marker& m : markers.markers)
      EXPECT_LT((fit.positions.row(m.vertex) - truth.row(m.vertex)).norm(), 1e-9) << m.name;
    double error = 0;
    for (int v : solver.cageVertices()) error += (fit.positions.row(v) - truth.row(v)).norm();
    error /= solver.cageVertices().size();
    // Straight segments cut the corners of the rest shirt's loops; the curves follow them (within 5.5 mm: the
    // deeper armhole's longer bicep loops put Catmull-Rom at 5.0 mm).
    EXPECT_LT(error, method == pcg::CurveMethod::Linear ? 0.015 : 0.0055) << "mean cage error " << error << " m";
  }
}

TEST(CageSplineSolver, NamesACurveWithoutMarkersAtItsEnds) {
  const auto& shirt = pixelcloth::testing::tshirt();
  const pcg::Cage cage = pcg::garmentCage(shirt);
  pcg::MarkerSet markers = pcg::placeMarkers(pcg::defineMarkers(shirt, cage), shirt.mesh.V);
  const pcg::CageCurve& side = *cage.findCurve("side_left");
  markers.markers.erase(std::remove_if(markers.markers.begin(), markers.markers.end(),
                                       [&](const pcg::Marker& m) { return m.vertex == side.vertices.front(); }),
                        markers.markers.end());
  const pcg::CageSplineSolver solver(shirt, cage, {});
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] { solver.solve(markers); }).find("side_left"), std::string::npos);
}
