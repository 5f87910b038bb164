#pragma once

// The residuals of the length-preserving cage spline (DESIGN.md, "Key-point-to-cage spline solver"), as templated
// functors for ceres::AutoDiffCostFunction. Deliberately free of Ceres includes: spline_solver.cpp wraps them, tests
// check them against numeric differentiation. Any scalar type with +, -, *, / and an ADL-visible sqrt works (double,
// ceres::Jet).
//
// A segment joins markers p0 and p1 whose rest arc length apart is L. Its shape is the cubic Hermite curve
//   x(t) = h00(t) p0 + h10(t) L d0 + h01(t) p1 + h11(t) L d1,  t in [0, 1],
// where d0 and d1 are the curve's derivatives with respect to rest arc length at the markers (unit length when the
// curve keeps its rest length locally). Neighbouring segments share a marker's d, so the spline is C1 in rest arc
// length.

#include <cmath>

namespace pixelcloth::cage {

/// Gauss-Legendre nodes and weights on [0, 1] (5 points: exact for polynomials up to degree 9).
struct GaussLegendre5 {
  static constexpr int kPoints = 5;
  static constexpr double kNodes[kPoints] = {0.04691007703066800, 0.23076534494715845, 0.5, 0.76923465505284155,
                                             0.95308992296933200};
  static constexpr double kWeights[kPoints] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                                               0.23931433524968324, 0.11846344252809454};
};

/// 2-point Gauss-Legendre on [0, 1]: exact for polynomials up to degree 3, so for the squared second derivative of a
/// cubic (degree 2).
struct GaussLegendre2 {
  static constexpr int kPoints = 2;
  static constexpr double kNodes[kPoints] = {0.21132486540518711, 0.78867513459481289};
  static constexpr double kWeights[kPoints] = {0.5, 0.5};
};

namespace detail {
/// dx/dt of the Hermite segment at t (3 values into `out`).
template <typename T>
void hermiteVelocity(const T* p0, const T* d0, const T* p1, const T* d1, double length, double t, T* out) {
  const double a = 6 * t * t - 6 * t, b = (3 * t * t - 4 * t + 1) * length, c = -a, d = (3 * t * t - 2 * t) * length;
  for (int k = 0; k < 3; ++k) out[k] = T(a) * p0[k] + T(b) * d0[k] + T(c) * p1[k] + T(d) * d1[k];
}
/// d2x/dt2 of the Hermite segment at t.
template <typename T>
void hermiteAcceleration(const T* p0, const T* d0, const T* p1, const T* d1, double length, double t, T* out) {
  const double a = 12 * t - 6, b = (6 * t - 4) * length, c = -a, d = (6 * t - 2) * length;
  for (int k = 0; k < 3; ++k) out[k] = T(a) * p0[k] + T(b) * d0[k] + T(c) * p1[k] + T(d) * d1[k];
}
}  // namespace detail

/// Arc length of the segment, integral of |dx/dt| over [0, 1] by 5-point Gauss-Legendre quadrature (metres).
template <typename T>
T hermiteArcLength(const T* p0, const T* d0, const T* p1, const T* d1, double length) {
  using std::sqrt;
  T sum = T(0);
  for (int g = 0; g < GaussLegendre5::kPoints; ++g) {
    T v[3];
    detail::hermiteVelocity(p0, d0, p1, d1, length, GaussLegendre5::kNodes[g], v);
    // The tiny constant keeps the derivative of sqrt finite where the velocity vanishes.
    sum += T(GaussLegendre5::kWeights[g]) * sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + T(1e-18));
  }
  return sum;
}

/// One residual: (arc length - L) / (tolerance L), the segment's relative length error in units of `tolerance`
/// (e.g. 0.01: a 1% error costs as much as a unit residual). With `stretch`, only a segment shorter than L costs:
/// worn cloth stretches (up to 15-20% near the armholes and the neckline of the simulated T-shirts, where the chord
/// between two markers is often longer than their rest distance) but keeps at least its rest length along a curve.
struct SegmentLengthResidual {
  template <typename T>
  bool operator()(const T* const p0, const T* const d0, const T* const p1, const T* const d1, T* residual) const {
    T excess = hermiteArcLength(p0, d0, p1, d1, restLength) - T(restLength);
    if (stretch && excess > T(0)) excess = T(0);
    residual[0] = excess / T(tolerance * restLength);
    return true;
  }
  double restLength = 1;
  double tolerance = 0.01;
  bool stretch = false;
};

/// 3 x 2 residuals: sqrt(weight w_g) x''(t_g) / L at the 2 Gauss-Legendre nodes, so that the squared sum is weight
/// times the integral over t of |x''|^2 / L^2, exactly (x'' is linear in t): the integral of (curvature x L)^2 over
/// the segment when |dx/dt| = L. A scale-free bending energy that keeps the tangents, which the lengths alone leave
/// free, smooth.
struct BendingResidual {
  template <typename T>
  bool operator()(const T* const p0, const T* const d0, const T* const p1, const T* const d1, T* residual) const {
    for (int g = 0; g < GaussLegendre2::kPoints; ++g) {
      T a[3];
      detail::hermiteAcceleration(p0, d0, p1, d1, restLength, GaussLegendre2::kNodes[g], a);
      const double scale = std::sqrt(weight * GaussLegendre2::kWeights[g]) / restLength;
      for (int k = 0; k < 3; ++k) residual[3 * g + k] = T(scale) * a[k];
    }
    return true;
  }
  static constexpr int kResiduals = 3 * GaussLegendre2::kPoints;
  double restLength = 1;
  double weight = 1;
};

/// 3 residuals: weight (d - prior): keeps a marker's tangent (derivative in rest arc length) near a prior, the
/// Catmull-Rom tangent, so that the length term changes the Catmull-Rom curve only as much as it must.
struct TangentPriorResidual {
  template <typename T>
  bool operator()(const T* const d, T* residual) const {
    for (int k = 0; k < 3; ++k) residual[k] = T(weight) * (d[k] - T(prior[k]));
    return true;
  }
  double prior[3] = {0, 0, 0};
  double weight = 1;
};

/// 3 residuals: (p - observed) / sigma, the soft fit of a noisy marker (sigma: its noise, metres).
struct MarkerFitResidual {
  template <typename T>
  bool operator()(const T* const p, T* residual) const {
    for (int k = 0; k < 3; ++k) residual[k] = (p[k] - T(observed[k])) / T(sigma);
    return true;
  }
  double observed[3] = {0, 0, 0};
  double sigma = 0.005;
};

}  // namespace pixelcloth::cage
