// Per-face values of a garment in pattern space, panels side by side with a colour bar: the area distortion of a
// dressing (before and after relaxation) and the appendix statistics of a dataset (area ratios, self-intersections).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <unordered_map>
#include <vector>

#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

using namespace cage;

namespace {
/// Blue (compressed to half the area or less) - white (none) - red (stretched to twice or more).
core::Color distortionColor(double areaRatio) {
  const double l = std::clamp(std::log2(std::max(areaRatio, 1e-12)), -1.0, 1.0);
  return toColor(viz::colorRamp(0.5 * (l + 1), /*diverging=*/true));
}

/// White (0) - red (`top` or more).
core::Color fractionColor(double value, double top) {
  return toColor(viz::colorRamp(0.5 + 0.5 * std::clamp(value / top, 0.0, 1.0), /*diverging=*/true));
}

std::string fixed(double x, int digits = 2) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", digits, x);
  return text;
}

/// The colour scale of a fraction picture: the largest value over every panel, at least 1%, rounded up to a tenth of
/// its power of ten (0.013 -> 0.02, 0.37 -> 0.4).
double fractionTop(const std::vector<FacePanel>& panels) {
  double top = 0.01;
  for (const FacePanel& panel : panels)
    if (panel.values.size() > 0) top = std::max(top, panel.values.maxCoeff());
  const double decade = std::pow(10.0, std::floor(std::log10(top)));
  return std::min(1.0, std::ceil(top / decade - 1e-9) * decade);
}

}  // namespace

core::RgbImage renderFacePanels(const garment::Garment& garment, const std::vector<FacePanel>& panels, FaceScale scale,
                                int pixelsPerMetre) {
  PIXELCLOTH_CHECK(pixelsPerMetre >= 10 && pixelsPerMetre <= 5000,
                   "renderFacePanels: pixelsPerMetre must be in [10, 5000], got " << pixelsPerMetre);
  PIXELCLOTH_CHECK(!panels.empty() && panels.size() <= 4, "renderFacePanels: 1 to 4 panels, got " << panels.size());
  const core::Mesh& mesh = garment.mesh;
  PIXELCLOTH_CHECK(mesh.hasUV() && garment.faceLayout.size() == mesh.numFaces(),
                   "renderFacePanels: garment '" << garment.name << "' lacks UVs or per-face layouts");
  for (const FacePanel& panel : panels)
    PIXELCLOTH_CHECK(panel.values.size() == mesh.numFaces(),
                     "renderFacePanels: panel '" << panel.title << "' has " << panel.values.size()
                                                 << " values, the garment " << mesh.numFaces() << " faces");
  const double ppm = pixelsPerMetre, margin = 0.03, layoutGap = 0.06;
  const int numLayouts = garment.numLayouts();
  const int textScale = std::max(1, pixelsPerMetre / 250);
  std::vector<Eigen::AlignedBox2d> bounds;
  std::vector<double> left(numLayouts, margin);
  double panelWidth = 2 * margin + layoutGap * (numLayouts - 1), layoutHeight = 0;
  for (int l = 0; l < numLayouts; ++l) {
    bounds.push_back(garment.layoutBounds(l));
    if (l > 0) left[l] = left[l - 1] + bounds[l - 1].sizes().x() + layoutGap;
    panelWidth += bounds[l].sizes().x();
    layoutHeight = std::max(layoutHeight, bounds[l].sizes().y());
  }
  const int count = static_cast<int>(panels.size());
  const int panelW = static_cast<int>(std::ceil(panelWidth * ppm));
  const int titleH = 28 * textScale, labelH = 10 * textScale;
  const int panelH = static_cast<int>(std::ceil((layoutHeight + 2 * margin) * ppm)) + labelH;
  const int gap = 10 * textScale, barH = 10 * textScale, barBlockH = barH + 22 * textScale;
  const int width = count * panelW + (count - 1) * gap, height = titleH + panelH + barBlockH;
  PIXELCLOTH_CHECK(static_cast<double>(width) * height <= 1e8,
                   "renderFacePanels: a " << width << " x " << height << " picture is too large; lower pixelsPerMetre");
  core::RgbImage image(width, height);
  const double top = scale == FaceScale::Fraction ? fractionTop(panels) : 1.0;
  auto colour = [&](double value) {
    return scale == FaceScale::AreaRatio ? distortionColor(value) : fractionColor(value, top);
  };

  // Edges on a layout's outline: used by one face of that layout.
  std::vector<std::unordered_map<std::uint64_t, int>> edgeUses(numLayouts);
  auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b));
  };
  for (int f = 0; f < mesh.numFaces(); ++f) {
    for (int k = 0; k < 3; ++k) ++edgeUses[garment.faceLayout[f]][key(mesh.F(f, k), mesh.F(f, (k + 1) % 3))];
  }

  for (int panel = 0; panel < count; ++panel) {
    const Eigen::VectorXd& values = panels[panel].values;
    const int x0 = panel * (panelW + gap), y0 = titleH + labelH;
    auto pixel = [&](int l, int uvRow) {
      const Eigen::Vector2d uv = mesh.UV.row(uvRow).transpose();
      return Eigen::Vector2d(x0 + (left[l] + uv.x() - bounds[l].min().x()) * ppm,
                             y0 + (margin + bounds[l].max().y() - uv.y()) * ppm);
    };
    for (int f = 0; f < mesh.numFaces(); ++f) {
      const int l = garment.faceLayout[f];
      viz::fillTriangle(image, pixel(l, mesh.FUV(f, 0)), pixel(l, mesh.FUV(f, 1)), pixel(l, mesh.FUV(f, 2)),
                        colour(values[f]));
    }
    for (int f = 0; f < mesh.numFaces(); ++f) {
      const int l = garment.faceLayout[f];
      for (int k = 0; k < 3; ++k) {
        const int j = (k + 1) % 3;
        if (edgeUses[l][key(mesh.F(f, k), mesh.F(f, j))] == 1)
          viz::drawLine(image, pixel(l, mesh.FUV(f, k)), pixel(l, mesh.FUV(f, j)), {60, 60, 60},
                        std::max(1.0, ppm / 500));
      }
    }
    const std::string& title = panels[panel].title;
    const int titleScale = viz::textExtent(title, 2 * textScale).x() <= panelW ? 2 * textScale : textScale;
    const Eigen::Vector2i extent = viz::textExtent(title, titleScale);
    viz::drawText(image, {x0 + (panelW - extent.x()) / 2, 2 * textScale}, title, {0, 0, 0}, titleScale);
    std::string stats;
    if (scale == FaceScale::AreaRatio) {
      std::vector<double> logs;
      for (int f = 0; f < values.size(); ++f) logs.push_back(std::log2(std::max(values[f], 1e-12)));
      stats = "log2 area ratio 5-95 pct " + fixed(core::quantile(logs, 0.05)) + " to " +
              fixed(core::quantile(logs, 0.95)) + "   min " + fixed(core::quantile(logs, 0)) + "   max " +
              fixed(core::quantile(logs, 1));
    } else {
      const double any = static_cast<double>((values.array() > 0).count()) / std::max<Eigen::Index>(1, values.size());
      stats = fixed(100 * any, 1) + "% of faces ever   most " + fixed(100 * values.maxCoeff(), 1) + "% of samples";
    }
    const Eigen::Vector2i statsExtent = viz::textExtent(stats, textScale);
    viz::drawText(image, {x0 + (panelW - statsExtent.x()) / 2, 19 * textScale}, stats, {60, 60, 60}, textScale);
    for (int l = 0; l < numLayouts; ++l) {
      const Eigen::Vector2i labelExtent = viz::textExtent(garment.layouts[l], textScale);
      const int centre = x0 + static_cast<int>((left[l] + 0.5 * bounds[l].sizes().x()) * ppm);
      viz::drawText(image, {centre - labelExtent.x() / 2, titleH + (labelH - labelExtent.y()) / 2}, garment.layouts[l],
                    {70, 70, 70}, textScale);
    }
  }

  // Colour bar: log2 of the area ratio from -1 (half the pattern area) to 1 (twice), or the fraction from 0 to top.
  const int barW = std::min(width - 4 * gap, 400 * textScale), barX = (width - barW) / 2, barY = titleH + panelH;
  for (int x = 0; x < barW; ++x) {
    const double t = (x + 0.5) / barW;
    const core::Color c =
        scale == FaceScale::AreaRatio ? toColor(viz::colorRamp(t, /*diverging=*/true)) : fractionColor(t * top, top);
    for (int y = 0; y < barH; ++y) image.set(barX + x, barY + y, c);
  }
  for (int x = barX - 1; x <= barX + barW; ++x) image.set(x, barY - 1, {0, 0, 0}), image.set(x, barY + barH, {0, 0, 0});
  for (int y = barY; y < barY + barH; ++y) image.set(barX - 1, y, {0, 0, 0}), image.set(barX + barW, y, {0, 0, 0});
  std::vector<std::pair<double, std::string>> ticks;
  if (scale == FaceScale::AreaRatio)
    ticks = {{0.0, "-1"}, {0.25, "-0.5"}, {0.5, "0"}, {0.75, "0.5"}, {1.0, "1"}};
  else
    ticks = {{0.0, "0%"}, {0.5, fixed(50 * top, 1) + "%"}, {1.0, fixed(100 * top, 1) + "%"}};
  for (const auto& [t, label] : ticks) {
    const int x = barX + static_cast<int>(std::lround(t * (barW - 1)));
    for (int y = barY + barH; y < barY + barH + 2 * textScale; ++y) image.set(x, y, {0, 0, 0});
    const Eigen::Vector2i extent = viz::textExtent(label, textScale);
    viz::drawText(image, {x - extent.x() / 2, barY + barH + 3 * textScale}, label, {0, 0, 0}, textScale);
  }
  const std::string caption =
      scale == FaceScale::AreaRatio ? "log2 area ratio   blue compressed   red stretched" : "fraction of samples";
  const Eigen::Vector2i extent = viz::textExtent(caption, textScale);
  viz::drawText(image, {(width - extent.x()) / 2, barY + barH + 12 * textScale}, caption, {0, 0, 0}, textScale);
  return image;
}

core::RgbImage renderAreaDistortion(const garment::Garment& garment, const Dressing& dressing, int pixelsPerMetre) {
  PIXELCLOTH_CHECK(dressing.areaRatioBefore.size() == garment.mesh.numFaces() &&
                       dressing.areaRatioAfter.size() == garment.mesh.numFaces(),
                   "renderAreaDistortion: the dressing has "
                       << dressing.areaRatioBefore.size() << " / " << dressing.areaRatioAfter.size()
                       << " area ratios, the garment " << garment.mesh.numFaces() << " faces");
  return renderFacePanels(
      garment, {{"before relaxation", dressing.areaRatioBefore}, {"after relaxation", dressing.areaRatioAfter}},
      FaceScale::AreaRatio, pixelsPerMetre);
}

}  // namespace pixelcloth::viz
