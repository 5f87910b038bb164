#include "pixelcloth/viz/pose_figures.h"

#include <algorithm>
#include <cmath>

#include "pixelcloth/core/error.h"
#include "pixelcloth/viz/draw.h"

namespace pixelcloth::viz {

namespace {

/// Count of `poses` in each bin of Euler angle `axis` of joint `joint` over [lower, upper].
std::vector<int> histogram(const std::vector<body::Pose>& poses, int joint, int axis, double lower, double upper,
                           int bins) {
  std::vector<int> counts(bins, 0);
  for (const body::Pose& pose : poses) {
    const double angle = body::eulerXZYFromRotation(pose.rotations[joint])(axis);
    ++counts[std::clamp(static_cast<int>((angle - lower) / (upper - lower) * bins), 0, bins - 1)];
  }
  return counts;
}

void fillRect(core::RgbImage& image, int x0, int y0, int x1, int y1, core::Color color, double alpha = 1.0) {
  for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) image.blend(x, y, color, alpha);
}

constexpr int kAxes[3] = {0, 2, 1};  // x (twist), z, y: the composition order
const char* const kAxisNames[3] = {"x", "y", "z"};

}  // namespace

core::RgbImage renderJointHistograms(const std::vector<PoseStage>& stages, int bins) {
  PIXELCLOTH_CHECK(bins >= 2, "histograms: need at least 2 bins, got " << bins);
  PIXELCLOTH_CHECK(!stages.empty() && stages.size() <= 4, "histograms: need 1 to 4 stages, got " << stages.size());
  const int panelW = 200, panelH = 110, margin = 14, columns = 3, rows = static_cast<int>(body::kPoseJoints.size());
  const int header = 14 + 14 * static_cast<int>(stages.size());
  core::RgbImage image(columns * (panelW + margin) + margin, header + rows * (panelH + margin) + margin);
  const core::Color black = {30, 30, 30};
  drawText(image, {margin, 6}, "joint angles in degrees; pose counts per bin", black, 1);
  for (size_t k = 0; k < stages.size(); ++k)
    drawText(image, {margin, 20 + 14 * static_cast<int>(k)},
             stages[k].label + " (" + std::to_string(stages[k].poses.size()) + ")", stages[k].color, 1);
  for (int joint = 0; joint < rows; ++joint) {
    const body::JointLimits& limits = body::jointLimits(body::kPoseJoints[joint]);
    for (int c = 0; c < columns; ++c) {
      const int axis = kAxes[c];
      const int x0 = margin + c * (panelW + margin), y0 = header + margin + joint * (panelH + margin);
      const int plotTop = y0 + 14, plotBottom = y0 + panelH - 12;
      fillRect(image, x0, plotTop, x0 + panelW, plotBottom, {245, 245, 245});
      drawText(image, {x0, y0}, body::kPoseJoints[joint] + " " + kAxisNames[axis], black);
      const double lower = limits.lower(axis), upper = limits.upper(axis);
      const std::string lo = std::to_string(static_cast<int>(std::lround(lower)));
      const std::string hi = std::to_string(static_cast<int>(std::lround(upper)));
      drawText(image, {x0, plotBottom + 3}, lo, black);
      drawText(image, {x0 + panelW - viz::textExtent(hi).x(), plotBottom + 3}, hi, black);
      if (upper - lower < 1e-9) {
        drawText(image, {x0 + 60, (plotTop + plotBottom) / 2}, "fixed", {170, 170, 170});
        continue;
      }
      std::vector<std::vector<int>> counts;
      int top = 0;
      for (const PoseStage& stage : stages) {
        counts.push_back(histogram(stage.poses, joint, axis, lower, upper, bins));
        top = std::max(top, *std::max_element(counts.back().begin(), counts.back().end()));
      }
      if (top == 0) continue;
      const double barW = static_cast<double>(panelW) / bins;
      const int height = plotBottom - plotTop;
      for (int b = 0; b < bins; ++b) {
        const int bx0 = x0 + static_cast<int>(b * barW), bx1 = x0 + static_cast<int>((b + 1) * barW) - 1;
        for (size_t k = 0; k < stages.size(); ++k) {
          const int inset = static_cast<int>(k);
          fillRect(image, bx0 + inset, plotBottom - counts[k][b] * height / top, bx1 - inset, plotBottom,
                   stages[k].color);
        }
      }
      if (lower < 0 && upper > 0) {  // the rest angle
        const double zx = x0 + (0 - lower) / (upper - lower) * panelW;
        drawLine(image, {zx, static_cast<double>(plotTop)}, {zx, static_cast<double>(plotBottom)}, black, 1.0);
      }
    }
  }
  return image;
}

JointBinLoss worstJointBin(const std::vector<body::Pose>& before, const std::vector<body::Pose>& after, int bins,
                           int minCount) {
  PIXELCLOTH_CHECK(bins >= 2, "joint bins: need at least 2 bins, got " << bins);
  JointBinLoss worst;
  for (size_t joint = 0; joint < body::kPoseJoints.size(); ++joint) {
    const body::JointLimits& limits = body::jointLimits(body::kPoseJoints[joint]);
    for (int c = 0; c < 3; ++c) {
      const int axis = kAxes[c];
      const double lower = limits.lower(axis), upper = limits.upper(axis);
      if (upper - lower < 1e-9) continue;
      const std::vector<int> hb = histogram(before, static_cast<int>(joint), axis, lower, upper, bins);
      const std::vector<int> ha = histogram(after, static_cast<int>(joint), axis, lower, upper, bins);
      for (int b = 0; b < bins; ++b) {
        if (hb[b] < minCount) continue;
        const JointBinLoss candidate{body::kPoseJoints[joint], kAxisNames[axis],
                                     lower + (upper - lower) * b / bins,
                                     lower + (upper - lower) * (b + 1) / bins, hb[b], ha[b]};
        if (worst.before == 0 || candidate.keptFraction() < worst.keptFraction()) worst = candidate;
      }
    }
  }
  return worst;
}

}  // namespace pixelcloth::viz
