// Training curves: per-vertex error on the train and regularisation splits, against the epoch and against wall time.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "pixelcloth/core/error.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"

namespace pixelcloth::viz {

namespace {

/// A wall time as a short axis label: seconds below two minutes, else minutes, else hours.
std::string durationLabel(double seconds) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(seconds < 120 ? 0 : 1);
  if (seconds < 120)
    text << seconds << " s";
  else if (seconds < 7200)
    text << seconds / 60 << " min";
  else
    text << seconds / 3600 << " h";
  return text.str();
}

}  // namespace

core::RgbImage renderTrainingCurves(const learn::NetworkReport& report, const std::string& model, int width, int height) {
  PIXELCLOTH_CHECK(!report.epochs.empty(), "training curves: the report has no epochs");
  PIXELCLOTH_CHECK(width >= 400 && height >= 150, "training curves: " << width << " x " << height << " is too small");
  core::RgbImage image(width, height);
  const core::Color black = {30, 30, 30}, grey = {200, 200, 200}, blue = {40, 100, 200}, orange = {230, 120, 20};
  const int top = 46, bottom = height - 30, gap = 40;
  // Log scale over the errors that are finite and positive, shared by both panels.
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const learn::EpochRecord& e : report.epochs)
    for (double v : {e.trainErrorCm, e.regularisationErrorCm})
      if (std::isfinite(v) && v > 0) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(hi > 0)) lo = 0.01, hi = 1;
  const double logLo = std::floor(std::log10(lo)), logHi = std::max(logLo + 1, std::ceil(std::log10(hi)));
  const int n = static_cast<int>(report.epochs.size());
  // Each epoch's end on the two horizontal axes: its number, and the wall time since the run began.
  std::vector<double> epochs(n), elapsed(n);
  double clock = 0;
  for (int k = 0; k < n; ++k) {
    epochs[k] = report.epochs[k].epoch;
    clock += std::max(0.0, report.epochs[k].seconds);
    elapsed[k] = clock;
  }
  drawText(image, {50, 6}, model, black, 2);
  drawText(image, {50, 26}, "per-vertex error in cm (log scale)", black);
  drawText(image, {50 + textExtent("per-vertex error in cm (log scale)").x() + 20, 26}, "train", blue);
  drawText(image, {50 + textExtent("per-vertex error in cm (log scale)").x() + 60, 26}, "regularisation", orange);
  const learn::EpochRecord& best = report.epochs[std::clamp(report.bestEpoch - 1, 0, n - 1)];
  const int bestIndex = std::clamp(report.bestEpoch - 1, 0, n - 1);

  // One panel: x from the values in `xs` (first to last epoch), labelled at both ends.
  auto panel = [&](int left, int right, const std::vector<double>& xs, double x0, const std::string& firstLabel,
                   const std::string& lastLabel) {
    const double span = xs.back() - x0;
    if (!(span > 0) && n > 1) {
      drawText(image, {left + 10, (top + bottom) / 2}, "no wall times recorded", black);
      return;
    }
    auto at = [&](int k, double value) {
      const double x = span > 0 ? (xs[k] - x0) / span : 0.5, y = (std::log10(value) - logLo) / (logHi - logLo);
      return Eigen::Vector2d(left + x * (right - left), bottom - y * (bottom - top));
    };
    for (double decade = logLo; decade <= logHi; ++decade)
      for (double step : {1.0, 2.0, 5.0}) {  // lines at 1, 2 and 5 times each power of ten
        const double value = step * std::pow(10.0, decade);
        if (std::log10(value) > logHi + 1e-9) break;
        const double y = bottom - (std::log10(value) - logLo) / (logHi - logLo) * (bottom - top);
        drawLine(image, {left, y}, {right, y}, step == 1.0 ? grey : core::Color{230, 230, 230});
        std::ostringstream label;
        label << value;
        drawText(image, {left - 46, static_cast<int>(y) - 3}, label.str(), black);
      }
    drawText(image, {left, bottom + 8}, firstLabel, black);
    drawText(image, {right - textExtent(lastLabel).x(), bottom + 8}, lastLabel, black);
    for (int split = 0; split < 2; ++split)
      for (int k = 0; k < n; ++k) {
        const double b = split ? report.epochs[k].regularisationErrorCm : report.epochs[k].trainErrorCm;
        if (!(std::isfinite(b) && b > 0)) continue;
        if (n == 1) drawDisc(image, at(k, b), 2, split ? orange : blue);
        if (k == 0) continue;
        const double a = split ? report.epochs[k - 1].regularisationErrorCm : report.epochs[k - 1].trainErrorCm;
        if (std::isfinite(a) && a > 0) drawLine(image, at(k - 1, a), at(k, b), split ? orange : blue, 2.0);
      }
    const double mark = std::isfinite(best.regularisationErrorCm) ? best.regularisationErrorCm : best.trainErrorCm;
    if (std::isfinite(mark) && mark > 0) drawDisc(image, at(bestIndex, mark), 4, black);
  };
  const int middle = width / 2;
  panel(50, middle - gap / 2, epochs, epochs.front() - (n > 1 ? 0 : 1),
        "epoch " + std::to_string(report.epochs.front().epoch), "epoch " + std::to_string(report.epochs.back().epoch));
  panel(middle + gap / 2 + 30, width - 16, elapsed, 0, "0 s", durationLabel(elapsed.back()) + " wall time");
  return image;
}

}  // namespace pixelcloth::viz
