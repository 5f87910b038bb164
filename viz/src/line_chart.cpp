// Line charts of small tables (the experiments' error against a parameter).
#include "pixelcloth/viz/line_chart.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/viz/draw.h"

namespace pixelcloth::viz {

namespace {
/// A tick spacing of 1, 2 or 5 times a power of ten giving about `count` intervals over `span`.
double niceStep(double span, int count) {
  const double raw = span / count, decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * decade >= raw) return m * decade;
  return 10 * decade;
}

std::string tickLabel(double value, double step) {
  std::ostringstream out;
  out.precision(std::max(0, -static_cast<int>(std::floor(std::log10(step)))));
  out << std::fixed << (std::abs(value) < 1e-12 * step ? 0.0 : value);
  return out.str();
}
}  // namespace

LineChart lineChartFromJson(const nlohmann::json& json, const std::string& context) {
  LineChart chart;
  chart.title = core::valueOr<std::string>(json, "title", "", context);
  chart.xLabel = core::valueOr<std::string>(json, "x_label", "", context);
  chart.yLabel = core::valueOr<std::string>(json, "y_label", "", context);
  const nlohmann::json& series = core::requireField(json, "series", context);
  PIXELCLOTH_CHECK(series.is_array() && !series.empty() && series.size() <= 12,
                   context << ": 'series' must be an array of 1 to 12 series, got " << series.type_name()
                           << (series.is_array() ? " of " + std::to_string(series.size()) : std::string()));
  for (size_t s = 0; s < series.size(); ++s) {
    const std::string where = context + ": series " + std::to_string(s);
    ChartSeries line;
    line.name = core::valueOr<std::string>(series[s], "name", "series " + std::to_string(s), where);
    for (const char* axis : {"x", "y"}) {
      const nlohmann::json& values = core::requireField(series[s], axis, where);
      PIXELCLOTH_CHECK(values.is_array(), where << ": '" << axis << "' is " << values.type_name()
                                                << ", expected an array of numbers");
      std::vector<double>& out = axis[0] == 'x' ? line.x : line.y;
      for (size_t i = 0; i < values.size(); ++i) {
        PIXELCLOTH_CHECK(values[i].is_number() && std::isfinite(values[i].get<double>()),
                         where << ": " << axis << "[" << i << "] is " << values[i].dump() << ", expected a finite number");
        out.push_back(values[i].get<double>());
      }
    }
    PIXELCLOTH_CHECK(line.x.size() == line.y.size(),
                     where << ": " << line.x.size() << " x values but " << line.y.size() << " y values");
    PIXELCLOTH_CHECK(!line.x.empty(), where << ": no points");
    chart.series.push_back(std::move(line));
  }
  return chart;
}

core::RgbImage renderLineChart(const LineChart& chart, int width, int height) {
  PIXELCLOTH_CHECK(width >= 320 && height >= 200, "line chart: " << width << " x " << height << " is too small");
  PIXELCLOTH_CHECK(!chart.series.empty(), "line chart: no series");
  double xLo = std::numeric_limits<double>::infinity(), xHi = -xLo, yLo = xLo, yHi = -xLo;
  for (const ChartSeries& s : chart.series) {
    PIXELCLOTH_CHECK(s.x.size() == s.y.size() && !s.x.empty(), "line chart: series '" << s.name << "' has "
                                                                << s.x.size() << " x and " << s.y.size() << " y");
    for (size_t i = 0; i < s.x.size(); ++i) {
      xLo = std::min(xLo, s.x[i]), xHi = std::max(xHi, s.x[i]);
      yLo = std::min(yLo, s.y[i]), yHi = std::max(yHi, s.y[i]);
    }
  }
  if (yLo > 0) yLo = 0;
  if (xHi - xLo < 1e-12) xLo -= 0.5, xHi += 0.5;
  if (yHi - yLo < 1e-12) yHi = yLo + 1;
  const double yStep = niceStep(yHi - yLo, 5), xStep = niceStep(xHi - xLo, 6);
  yLo = std::floor(yLo / yStep) * yStep, yHi = std::ceil(yHi / yStep) * yStep;

  core::RgbImage image(width, height);
  const core::Color black = {30, 30, 30}, grey = {210, 210, 210};
  const int left = 60, right = width - 20, top = 56, bottom = height - 40;
  auto at = [&](double x, double y) {
    return Eigen::Vector2d(left + (x - xLo) / (xHi - xLo) * (right - left), bottom - (y - yLo) / (yHi - yLo) * (bottom - top));
  };
  for (double y = yLo; y <= yHi + 1e-9 * yStep; y += yStep) {
    const Eigen::Vector2d a = at(xLo, y);
    drawLine(image, a, at(xHi, y), grey);
    const std::string label = tickLabel(y, yStep);
    drawText(image, {left - 6 - textExtent(label).x(), static_cast<int>(a.y()) - 3}, label, black);
  }
  for (double x = std::ceil(xLo / xStep) * xStep; x <= xHi + 1e-9 * xStep; x += xStep) {
    const Eigen::Vector2d a = at(x, yLo);
    drawLine(image, a, a + Eigen::Vector2d(0, 4), black);
    const std::string label = tickLabel(x, xStep);
    drawText(image, {static_cast<int>(a.x()) - textExtent(label).x() / 2, bottom + 8}, label, black);
  }
  drawLine(image, at(xLo, yLo), at(xHi, yLo), black);
  drawLine(image, at(xLo, yLo), at(xLo, yHi), black);
  drawText(image, {left, 6}, chart.title, black, 2);
  drawText(image, {left, 26}, chart.yLabel, black);
  drawText(image, {right - textExtent(chart.xLabel).x(), bottom + 24}, chart.xLabel, black);
  int legend = left;
  for (size_t s = 0; s < chart.series.size(); ++s) {
    const core::Color color = paletteColor(static_cast<int>(s));
    drawDisc(image, Eigen::Vector2d(legend + 3, 42), 3, color);
    drawText(image, {legend + 10, 39}, chart.series[s].name, color);
    legend += 24 + textExtent(chart.series[s].name).x();
    const ChartSeries& line = chart.series[s];
    for (size_t i = 0; i < line.x.size(); ++i) {
      if (i > 0) drawLine(image, at(line.x[i - 1], line.y[i - 1]), at(line.x[i], line.y[i]), color, 2.0);
      drawDisc(image, at(line.x[i], line.y[i]), 3, color);
    }
  }
  return image;
}

}  // namespace pixelcloth::viz
