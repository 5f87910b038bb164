// The area-distortion picture of a dressing: pattern space, before and after relaxation, with a colour bar.
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
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

using namespace cage;

namespace {
/// Blue (compressed to half the area or less) - white (none) - red (stretched to twice or more).
core::Color distortionColor(double areaRatio) {
  const double l = std::clamp(std::log2(std::max(areaRatio, 1e-12)), -1.0, 1.0);
  return toColor(viz::colorRamp(0.5 * (l + 1), /*diverging=*/true));
}

std::string fixed2(double x) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", x);
  return text;
}

}  // namespace

core::RgbImage renderAreaDistortion(const garment::Garment& garment, const Dressing& dressing, int pixelsPerMetre) {
  PIXELCLOTH_CHECK(pixelsPerMetre >= 10 && pixelsPerMetre <= 5000,
                   "renderAreaDistortion: pixelsPerMetre must be in [10, 5000], got " << pixelsPerMetre);
  const core::Mesh& mesh = garment.mesh;
  PIXELCLOTH_CHECK(mesh.hasUV() && garment.faceLayout.size() == mesh.numFaces(),
                   "renderAreaDistortion: garment '" << garment.name << "' lacks UVs or per-face layouts");
  PIXELCLOTH_CHECK(
      dressing.areaRatioBefore.size() == mesh.numFaces() && dressing.areaRatioAfter.size() == mesh.numFaces(),
      "renderAreaDistortion: the dressing has " << dressing.areaRatioBefore.size() << " / "
                                                << dressing.areaRatioAfter.size() << " area ratios, the garment "
                                                << mesh.numFaces() << " faces");
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
  const int panelW = static_cast<int>(std::ceil(panelWidth * ppm));
  const int titleH = 28 * textScale, labelH = 10 * textScale;
  const int panelH = static_cast<int>(std::ceil((layoutHeight + 2 * margin) * ppm)) + labelH;
  const int gap = 10 * textScale, barH = 10 * textScale, barBlockH = barH + 22 * textScale;
  const int width = 2 * panelW + gap, height = titleH + panelH + barBlockH;
  PIXELCLOTH_CHECK(static_cast<double>(width) * height <= 1e8, "renderAreaDistortion: a "
                                                                   << width << " x " << height
                                                                   << " picture is too large; lower pixelsPerMetre");
  core::RgbImage image(width, height);

  // Edges on a layout's outline: used by one face of that layout.
  std::vector<std::unordered_map<std::uint64_t, int>> edgeUses(numLayouts);
  auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b));
  };
  for (int f = 0; f < mesh.numFaces(); ++f) {
    for (int k = 0; k < 3; ++k) ++edgeUses[garment.faceLayout[f]][key(mesh.F(f, k), mesh.F(f, (k + 1) % 3))];
  }

  const Eigen::VectorXd* ratios[2] = {&dressing.areaRatioBefore, &dressing.areaRatioAfter};
  const std::string titles[2] = {"before relaxation", "after relaxation"};
  for (int panel = 0; panel < 2; ++panel) {
    const int x0 = panel * (panelW + gap), y0 = titleH + labelH;
    auto pixel = [&](int l, int uvRow) {
      const Eigen::Vector2d uv = mesh.UV.row(uvRow).transpose();
      return Eigen::Vector2d(x0 + (left[l] + uv.x() - bounds[l].min().x()) * ppm,
                             y0 + (margin + bounds[l].max().y() - uv.y()) * ppm);
    };
    std::vector<double> logs;
    for (int f = 0; f < mesh.numFaces(); ++f) {
      const int l = garment.faceLayout[f];
      const double ratio = (*ratios[panel])[f];
      logs.push_back(std::log2(std::max(ratio, 1e-12)));
      viz::fillTriangle(image, pixel(l, mesh.FUV(f, 0)), pixel(l, mesh.FUV(f, 1)), pixel(l, mesh.FUV(f, 2)),
                        distortionColor(ratio));
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
    const Eigen::Vector2i extent = viz::textExtent(titles[panel], 2 * textScale);
    viz::drawText(image, {x0 + (panelW - extent.x()) / 2, 2 * textScale}, titles[panel], {0, 0, 0}, 2 * textScale);
    const std::string stats = "log2 area ratio 5-95 pct " + fixed2(core::quantile(logs, 0.05)) + " to " +
                              fixed2(core::quantile(logs, 0.95)) + "   min " + fixed2(core::quantile(logs, 0)) +
                              "   max " + fixed2(core::quantile(logs, 1));
    const Eigen::Vector2i statsExtent = viz::textExtent(stats, textScale);
    viz::drawText(image, {x0 + (panelW - statsExtent.x()) / 2, 19 * textScale}, stats, {60, 60, 60}, textScale);
    for (int l = 0; l < numLayouts; ++l) {
      const Eigen::Vector2i labelExtent = viz::textExtent(garment.layouts[l], textScale);
      const int centre = x0 + static_cast<int>((left[l] + 0.5 * bounds[l].sizes().x()) * ppm);
      viz::drawText(image, {centre - labelExtent.x() / 2, titleH + (labelH - labelExtent.y()) / 2}, garment.layouts[l],
                    {70, 70, 70}, textScale);
    }
  }

  // Colour bar: log2 of the area ratio from -1 (half the pattern area) to 1 (twice).
  const int barW = std::min(width - 4 * gap, 400 * textScale), barX = (width - barW) / 2, barY = titleH + panelH;
  for (int x = 0; x < barW; ++x) {
    const core::Color c = toColor(viz::colorRamp((x + 0.5) / barW, /*diverging=*/true));
    for (int y = 0; y < barH; ++y) image.set(barX + x, barY + y, c);
  }
  for (int x = barX - 1; x <= barX + barW; ++x) image.set(x, barY - 1, {0, 0, 0}), image.set(x, barY + barH, {0, 0, 0});
  for (int y = barY; y < barY + barH; ++y) image.set(barX - 1, y, {0, 0, 0}), image.set(barX + barW, y, {0, 0, 0});
  const std::pair<double, std::string> ticks[] = {{0.0, "-1"}, {0.25, "-0.5"}, {0.5, "0"}, {0.75, "0.5"}, {1.0, "1"}};
  for (const auto& [t, label] : ticks) {
    const int x = barX + static_cast<int>(std::lround(t * (barW - 1)));
    for (int y = barY + barH; y < barY + barH + 2 * textScale; ++y) image.set(x, y, {0, 0, 0});
    const Eigen::Vector2i extent = viz::textExtent(label, textScale);
    viz::drawText(image, {x - extent.x() / 2, barY + barH + 3 * textScale}, label, {0, 0, 0}, textScale);
  }
  const std::string caption = "log2 area ratio   blue compressed   red stretched";
  const Eigen::Vector2i extent = viz::textExtent(caption, textScale);
  viz::drawText(image, {(width - extent.x()) / 2, barY + barH + 12 * textScale}, caption, {0, 0, 0}, textScale);
  return image;
}

}  // namespace pixelcloth::viz
