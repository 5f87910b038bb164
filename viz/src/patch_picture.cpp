// Pictures of patches and the cage curves between them.
#include "pixelcloth/viz/patch_picture.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "pixelcloth/core/error.h"
#include "pixelcloth/patches/frame.h"
#include "pixelcloth/viz/draw.h"

namespace pixelcloth::viz {

using namespace patches;

namespace {

core::Color kindColor(garment::CurveKind kind) {
  switch (kind) {
    case garment::CurveKind::Seam:
      return {170, 20, 30};
    case garment::CurveKind::Loop:
      return {20, 70, 200};
    case garment::CurveKind::CentreLine:
      return {20, 140, 40};
    case garment::CurveKind::Opening:
      return {20, 20, 20};
    case garment::CurveKind::Split:
      return {235, 130, 0};
  }
  return {120, 120, 120};
}

/// A light tint of the palette colour of patch `id` (neighbouring ids get well separated colours).
core::Color patchTint(int id) {
  core::Color c = viz::paletteColor(id * 5);
  for (auto& channel : c) channel = static_cast<std::uint8_t>(std::lround(255 * 0.55 + channel * 0.45));
  return c;
}

}  // namespace

core::RgbImage renderPatches(const garment::Garment& garment, const std::vector<Patch>& patches,
                             const std::vector<PictureCurve>& curves, int size) {
  PIXELCLOTH_CHECK(size >= 64 && size <= 4096, "renderPatches: size must be in [64, 4096], got " << size);
  const int numLayouts = garment.numLayouts(), gap = size / 32, title = size / 16;
  const int textScale = std::max(1, size / 256);
  core::RgbImage image(numLayouts * size + (numLayouts - 1) * gap, size + title);
  std::vector<ImageFrame> frames;
  for (int l = 0; l < numLayouts; ++l) frames.push_back(layoutFrame(garment, l, size));
  auto pixel = [&](int l, int v) {
    Eigen::Vector2d uv = garment.mesh.UV.row(garment.vertexUV(v, l)).transpose();
    return Eigen::Vector2d(frames[l].toPixel(uv) + Eigen::Vector2d(l * (size + gap), title));
  };
  for (int l = 0; l < numLayouts; ++l) {
    const Eigen::Vector2i extent = viz::textExtent(garment.layouts[l], 2 * textScale);
    viz::drawText(image, {l * (size + gap) + (size - extent.x()) / 2, (title - extent.y()) / 2}, garment.layouts[l],
                  {0, 0, 0}, 2 * textScale);
  }

  const core::Mesh& mesh = garment.mesh;
  for (const Patch& patch : patches) {
    for (int f : patch.faces) {
      fillTriangle(image, pixel(patch.layout, mesh.F(f, 0)), pixel(patch.layout, mesh.F(f, 1)),
                   pixel(patch.layout, mesh.F(f, 2)), patchTint(patch.id));
    }
  }
  // Mesh edges of each layout: a curve edge is drawn where it is an edge of that layout.
  std::vector<std::set<std::pair<int, int>>> layoutEdges(numLayouts);
  for (int f = 0; f < mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      layoutEdges[garment.faceLayout[f]].insert(std::minmax(mesh.F(f, k), mesh.F(f, (k + 1) % 3)));
  const double width = std::max(2.0, size / 150.0);
  // Openings and seams first, lines over them.
  for (int pass = 0; pass < 2; ++pass) {
    for (const PictureCurve& curve : curves) {
      const bool boundary = curve.kind == garment::CurveKind::Seam || curve.kind == garment::CurveKind::Opening;
      if (boundary != (pass == 0)) continue;
      const size_t n = curve.vertices.size();
      for (size_t i = 0; i + (curve.closed ? 0 : 1) < n; ++i) {
        const int a = curve.vertices[i], b = curve.vertices[(i + 1) % n];
        for (int l = 0; l < numLayouts; ++l) {
          if (layoutEdges[l].count(std::minmax(a, b)))
            viz::drawLine(image, pixel(l, a), pixel(l, b), kindColor(curve.kind), width);
        }
      }
    }
  }
  for (const Patch& patch : patches) {
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    double area = 0;
    for (int f : patch.faces) {
      const Eigen::Vector2d a = pixel(patch.layout, mesh.F(f, 0)), b = pixel(patch.layout, mesh.F(f, 1)),
                            c = pixel(patch.layout, mesh.F(f, 2));
      const double w = 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
      centroid += w * (a + b + c) / 3.0;
      area += w;
    }
    if (area > 0) centroid /= area;
    const std::string label = std::to_string(patch.id);
    const Eigen::Vector2i extent = viz::textExtent(label, textScale);
    viz::drawText(image,
                  {static_cast<int>(std::lround(centroid.x())) - extent.x() / 2,
                   static_cast<int>(std::lround(centroid.y())) - extent.y() / 2},
                  label, {0, 0, 0}, textScale);
  }
  return image;
}

}  // namespace pixelcloth::viz
