// The flat pattern drawn for people: layouts side by side, panels tinted, seams in matching colours.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

#include "pixelcloth/core/edge_key.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"

namespace pixelcloth::viz {

using core::Color;
using core::RgbImage;
using garment::Garment;

namespace {

using core::edgeKey;

/// Colour of the i-th seam: the categorical palette without its grey (too close to the triangle edges) and its two
/// pale colours (invisible on the tinted panels), completed by darker blue, green and red.
Color seamColor(int i) {
  const int k = i % 12;
  if (k < 7) return paletteColor(k);
  if (k < 9) return paletteColor(k + 1);
  static const int kDarkened[] = {0, 2, 3};
  Color c = paletteColor(kDarkened[k - 9]);
  for (auto& channel : c) channel = static_cast<std::uint8_t>(channel / 2);
  return c;
}

}  // namespace

RgbImage renderPattern(const Garment& garment, int pixelsPerMetre) {
  PIXELCLOTH_CHECK(pixelsPerMetre >= 10 && pixelsPerMetre <= 10000,
                   "renderPattern: pixelsPerMetre must be in [10, 10000], got " << pixelsPerMetre);
  PIXELCLOTH_CHECK(garment.mesh.hasUV() && garment.faceLayout.size() == garment.mesh.numFaces() &&
                       garment.facePanel.size() == garment.mesh.numFaces(),
                   "renderPattern: garment '" << garment.name << "' lacks UVs or per-face layout / panel indices");
  const double ppm = pixelsPerMetre, margin = 0.03, gap = 0.08;
  const int numLayouts = garment.numLayouts();
  std::vector<Eigen::AlignedBox2d> bounds;
  double totalWidth = 2 * margin + gap * (numLayouts - 1), maxHeight = 0;
  for (int l = 0; l < numLayouts; ++l) {
    bounds.push_back(garment.layoutBounds(l));
    totalWidth += bounds.back().sizes().x();
    maxHeight = std::max(maxHeight, bounds.back().sizes().y());
  }
  const int width = static_cast<int>(std::ceil(totalWidth * ppm)),
            height = static_cast<int>(std::ceil((maxHeight + 2 * margin) * ppm));
  PIXELCLOTH_CHECK(static_cast<double>(width) * height <= 1e8,
                   "renderPattern: a " << width << " x " << height << " picture is too large; lower pixelsPerMetre");
  RgbImage image(width, height);
  // Pixel position of a UV in layout l: layouts side by side, tops aligned, v up => rows down.
  std::vector<double> left(numLayouts, margin);
  for (int l = 1; l < numLayouts; ++l) left[l] = left[l - 1] + bounds[l - 1].sizes().x() + gap;
  auto pixel = [&](int l, int uvRow) {
    Eigen::Vector2d uv = garment.mesh.UV.row(uvRow);
    return Eigen::Vector2d((left[l] + uv.x() - bounds[l].min().x()) * ppm,
                           (margin + bounds[l].max().y() - uv.y()) * ppm);
  };
  const auto& F = garment.mesh.F;
  const auto& FUV = garment.mesh.FUV;
  auto mix = [](Color a, Color b, double t) {
    Color c;
    for (int i = 0; i < 3; ++i) c[i] = static_cast<std::uint8_t>(std::lround(a[i] * (1 - t) + b[i] * t));
    return c;
  };
  for (int f = 0; f < F.rows(); ++f) {
    int l = garment.faceLayout[f];
    fillTriangle(image, pixel(l, FUV(f, 0)), pixel(l, FUV(f, 1)), pixel(l, FUV(f, 2)),
                 mix({255, 255, 255}, paletteColor(garment.facePanel[f]), 0.22));
  }
  // Undirected edges of each layout (vertex pairs), drawn once; also used to find where a seam runs.
  std::vector<std::unordered_set<std::uint64_t>> layoutEdges(numLayouts);
  const double thin = std::max(1.0, ppm / 1500);
  for (int f = 0; f < F.rows(); ++f) {
    int l = garment.faceLayout[f];
    for (int k = 0; k < 3; ++k) {
      int j = (k + 1) % 3;
      if (layoutEdges[l].insert(edgeKey(F(f, k), F(f, j))).second) {
        drawLine(image, pixel(l, FUV(f, k)), pixel(l, FUV(f, j)), {165, 165, 165}, thin);
      }
    }
  }
  auto drawChain = [&](const std::vector<int>& chain, bool closed, Color color, double lineWidth) {
    const size_t n = chain.size();
    for (size_t i = 0; i + (closed ? 0 : 1) < n; ++i) {
      int a = chain[i], b = chain[(i + 1) % n];
      for (int l = 0; l < numLayouts; ++l) {
        if (!layoutEdges[l].count(edgeKey(a, b))) continue;
        int ua = garment.vertexUV(a, l), ub = garment.vertexUV(b, l);
        if (ua >= 0 && ub >= 0) drawLine(image, pixel(l, ua), pixel(l, ub), color, lineWidth);
      }
    }
  };
  for (const auto& opening : garment.openings)
    drawChain(opening.vertices, true, {40, 40, 40}, std::max(2.0, ppm / 400));
  for (const auto& line : garment.lines) drawChain(line.vertices, line.closed, {30, 30, 120}, std::max(2.0, ppm / 400));
  for (size_t s = 0; s < garment.seams.size(); ++s) {
    drawChain(garment.seams[s].vertices, false, seamColor(static_cast<int>(s)), std::max(3.0, ppm / 250));
  }
  return image;
}

}  // namespace pixelcloth::viz
