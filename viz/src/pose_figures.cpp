#include "pixelcloth/viz/pose_figures.h"

#include <algorithm>
#include <cmath>

#include "pixelcloth/core/error.h"
#include "pixelcloth/viz/draw.h"

namespace pixelcloth::viz {

namespace {

/// Fraction of `poses` in each bin of Euler angle `axis` of joint `joint` over [lower, upper].
std::vector<double> histogram(const std::vector<body::Pose>& poses, int joint, int axis, double lower, double upper,
                              int bins) {
  std::vector<double> counts(bins, 0.0);
  for (const body::Pose& pose : poses) {
    const double angle = body::eulerXZYFromRotation(pose.rotations[joint])(axis);
    const int bin = std::clamp(static_cast<int>((angle - lower) / (upper - lower) * bins), 0, bins - 1);
    counts[bin] += 1.0;
  }
  if (!poses.empty())
    for (double& c : counts) c /= static_cast<double>(poses.size());
  return counts;
}

void fillRect(core::RgbImage& image, int x0, int y0, int x1, int y1, core::Color color, double alpha = 1.0) {
  for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) image.blend(x, y, color, alpha);
}

}  // namespace

core::RgbImage renderJointHistograms(const std::vector<body::Pose>& before, const std::vector<body::Pose>& after,
                                     int bins) {
  PIXELCLOTH_CHECK(bins >= 2, "histograms: need at least 2 bins, got " << bins);
  const int panelW = 200, panelH = 110, margin = 14, columns = 3, rows = static_cast<int>(body::kPoseJoints.size());
  const int header = 40;
  core::RgbImage image(columns * (panelW + margin) + margin, header + rows * (panelH + margin) + margin);
  const core::Color grey = {170, 170, 170}, blue = {40, 100, 200}, black = {30, 30, 30};
  drawText(image, {margin, 8}, "joint angles: before filtering (" + std::to_string(before.size()) + ", grey)", black,
           2);
  drawText(image, {margin, 26}, "after filtering (" + std::to_string(after.size()) + ", blue); degrees", blue, 1);
  const int axes[3] = {0, 2, 1};  // x (twist), z, y: the composition order
  const char* axisNames[3] = {"x", "y", "z"};
  for (int joint = 0; joint < rows; ++joint) {
    const body::JointLimits& limits = body::jointLimits(body::kPoseJoints[joint]);
    for (int c = 0; c < columns; ++c) {
      const int axis = axes[c];
      const int x0 = margin + c * (panelW + margin), y0 = header + margin + joint * (panelH + margin);
      const int plotTop = y0 + 14, plotBottom = y0 + panelH - 12;
      fillRect(image, x0, plotTop, x0 + panelW, plotBottom, {245, 245, 245});
      drawText(image, {x0, y0}, body::kPoseJoints[joint] + " " + axisNames[axis], black);
      const double lower = limits.lower(axis), upper = limits.upper(axis);
      const std::string lo = std::to_string(static_cast<int>(std::lround(lower)));
      const std::string hi = std::to_string(static_cast<int>(std::lround(upper)));
      drawText(image, {x0, plotBottom + 3}, lo, black);
      drawText(image, {x0 + panelW - viz::textExtent(hi).x(), plotBottom + 3}, hi, black);
      if (upper - lower < 1e-9) {
        drawText(image, {x0 + 60, (plotTop + plotBottom) / 2}, "fixed", grey);
        continue;
      }
      const std::vector<double> hb = histogram(before, joint, axis, lower, upper, bins);
      const std::vector<double> ha = histogram(after, joint, axis, lower, upper, bins);
      const double top = std::max(*std::max_element(hb.begin(), hb.end()), *std::max_element(ha.begin(), ha.end()));
      if (top <= 0) continue;
      const double barW = static_cast<double>(panelW) / bins;
      for (int b = 0; b < bins; ++b) {
        const int bx0 = x0 + static_cast<int>(b * barW), bx1 = x0 + static_cast<int>((b + 1) * barW) - 1;
        const int height = plotBottom - plotTop;
        fillRect(image, bx0, plotBottom - static_cast<int>(hb[b] / top * height), bx1, plotBottom, grey);
        fillRect(image, bx0 + 2, plotBottom - static_cast<int>(ha[b] / top * height), bx1 - 2, plotBottom, blue, 0.75);
      }
      if (lower < 0 && upper > 0) {  // the rest angle
        const double zx = x0 + (0 - lower) / (upper - lower) * panelW;
        drawLine(image, {zx, static_cast<double>(plotTop)}, {zx, static_cast<double>(plotBottom)}, black, 1.0);
      }
    }
  }
  return image;
}

}  // namespace pixelcloth::viz
