#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/core/image.h"

namespace pixelcloth::viz {

/// One line of a chart: points (x[i], y[i]) joined in the order given, each marked by a dot.
struct ChartSeries {
  std::string name;
  std::vector<double> x, y;
};

/// A line chart: linear axes fitted to the data (y from 0 when every value is positive), a legend of the series'
/// names in palette colours, the title above and the axis labels beside.
struct LineChart {
  std::string title, xLabel, yLabel;
  std::vector<ChartSeries> series;
};

/// Reads a chart from JSON {"title", "x_label", "y_label", "series": [{"name", "x": [...], "y": [...]}, ...]}. Throws
/// InputError naming `context` (the file) for a missing field, a value that is not a finite number, x and y of
/// different lengths, no point at all or more than 12 series.
LineChart lineChartFromJson(const nlohmann::json& json, const std::string& context);

/// Draws `chart` (width >= 320, height >= 200).
core::RgbImage renderLineChart(const LineChart& chart, int width = 640, int height = 400);

}  // namespace pixelcloth::viz
