#pragma once
// Small measuring helpers shared by the stages that report figures: wall time since a start, and quantiles.

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace pixelcloth::core {

/// Seconds of wall time since `start` (a steady clock's reading).
inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The q-quantile (q in [0, 1]) of `values`, linearly interpolated between the two nearest ranks; 0 when empty.
inline double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const double position = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(position)), hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (position - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

/// Mean per-vertex distance between two #V x 3 position arrays in metres, in centimetres: the error figure every stage
/// reports (any Eigen expressions of matching size; float arrays are promoted).
template <typename A, typename B>
double meanVertexErrorCm(const Eigen::MatrixBase<A>& positions, const Eigen::MatrixBase<B>& truth) {
  return 100 * (positions.template cast<double>() - truth.template cast<double>()).rowwise().norm().mean();
}

}  // namespace pixelcloth::core
