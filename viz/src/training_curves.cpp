// Training curves: per-vertex error on the train and regularisation splits, epoch by epoch.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "pixelcloth/core/error.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"

namespace pixelcloth::viz {

core::RgbImage renderTrainingCurves(const learn::NetworkReport& report, const std::string& model, int width, int height) {
  PIXELCLOTH_CHECK(!report.epochs.empty(), "training curves: the report has no epochs");
  PIXELCLOTH_CHECK(width >= 200 && height >= 150, "training curves: " << width << " x " << height << " is too small");
  core::RgbImage image(width, height);
  const core::Color black = {30, 30, 30}, grey = {200, 200, 200}, blue = {40, 100, 200}, orange = {230, 120, 20};
  const int left = 50, right = width - 16, top = 40, bottom = height - 30;
  // Log scale over the errors that are finite and positive.
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const learn::EpochRecord& e : report.epochs)
    for (double v : {e.trainErrorCm, e.regularisationErrorCm})
      if (std::isfinite(v) && v > 0) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(hi > 0)) lo = 0.01, hi = 1;
  const double logLo = std::floor(std::log10(lo)), logHi = std::max(logLo + 1, std::ceil(std::log10(hi)));
  const int n = static_cast<int>(report.epochs.size());
  auto at = [&](int epoch, double value) {
    const double x = n == 1 ? 0.5 : (epoch - 1.0) / (n - 1.0), y = (std::log10(value) - logLo) / (logHi - logLo);
    return Eigen::Vector2d(left + x * (right - left), bottom - y * (bottom - top));
  };
  for (double decade = logLo; decade <= logHi; ++decade) {
    const double y = bottom - (decade - logLo) / (logHi - logLo) * (bottom - top);
    drawLine(image, {left, y}, {right, y}, grey);
    std::ostringstream label;
    label << std::pow(10.0, decade);
    drawText(image, {4, static_cast<int>(y) - 3}, label.str(), black);
  }
  drawText(image, {left, 6}, model, black, 2);
  drawText(image, {left, 24}, "per-vertex error in cm (log scale)", black);
  drawText(image, {left + 230, 24}, "train", blue);
  drawText(image, {left + 270, 24}, "regularisation", orange);
  drawText(image, {left, bottom + 8}, "epoch 1", black);
  const std::string last = "epoch " + std::to_string(n);
  drawText(image, {right - textExtent(last).x(), bottom + 8}, last, black);
  for (int split = 0; split < 2; ++split) {
    for (int k = 1; k < n; ++k) {
      const double a = split ? report.epochs[k - 1].regularisationErrorCm : report.epochs[k - 1].trainErrorCm;
      const double b = split ? report.epochs[k].regularisationErrorCm : report.epochs[k].trainErrorCm;
      if (std::isfinite(a) && std::isfinite(b) && a > 0 && b > 0)
        drawLine(image, at(k, a), at(k + 1, b), split ? orange : blue, 2.0);
    }
  }
  const learn::EpochRecord& best = report.epochs[std::max(0, report.bestEpoch - 1)];
  const double mark = std::isfinite(best.regularisationErrorCm) ? best.regularisationErrorCm : best.trainErrorCm;
  if (std::isfinite(mark) && mark > 0) drawDisc(image, at(best.epoch, mark), 4, black);
  return image;
}

}  // namespace pixelcloth::viz
