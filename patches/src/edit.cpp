#include "pixelcloth/patches/edit.h"

#include <cmath>
#include <functional>

#include "pixelcloth/core/error.h"

namespace pixelcloth::patches {

namespace {

/// Calls `edit(layer, x, y, alpha)` for every non-empty pixel with alpha > 0 of every layer.
void forEachPixel(ClothImage& image, const Eigen::MatrixXf& region,
                  const std::function<void(ClothLayer&, int, int, float)>& edit) {
  image.validate();
  const int W = image.width, H = image.height, L = static_cast<int>(image.layers.size());
  const bool whole = region.size() == 0, perLayer = region.rows() == H && region.cols() == W;
  const bool sideBySide = region.rows() == H && region.cols() == L * W;
  PIXELCLOTH_CHECK(whole || perLayer || sideBySide, "edit region is " << region.cols() << " x " << region.rows()
                                                                      << ", expected " << W << " x " << H << " or "
                                                                      << L * W << " x " << H);
  PIXELCLOTH_CHECK(region.allFinite() && (whole || (region.minCoeff() >= 0 && region.maxCoeff() <= 1)),
                   "edit region values must be in [0, 1]");
  for (int l = 0; l < L; ++l) {
    ClothLayer& layer = image.layers[l];
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        if (layer.mask(y, x) < 0.5f) continue;
        float alpha = whole ? 1.0f : perLayer ? region(y, x) : region(y, l * W + x);
        if (alpha > 0) edit(layer, x, y, alpha);
      }
  }
}

}  // namespace

void shiftImage(ClothImage& image, float du, float dv, const Eigen::MatrixXf& region) {
  PIXELCLOTH_CHECK(std::isfinite(du) && std::isfinite(dv), "shift must be finite, got " << du << ", " << dv);
  forEachPixel(image, region, [&](ClothLayer& layer, int x, int y, float alpha) {
    layer.du(y, x) += alpha * du;
    layer.dv(y, x) += alpha * dv;
  });
}

void inflateImage(ClothImage& image, float scale, float add, const Eigen::MatrixXf& region) {
  PIXELCLOTH_CHECK(std::isfinite(scale) && std::isfinite(add),
                   "inflate scale and amount must be finite, got " << scale << ", " << add);
  forEachPixel(image, region, [&](ClothLayer& layer, int x, int y, float alpha) {
    float& dn = layer.dn(y, x);
    dn += alpha * ((scale - 1.0f) * dn + add);
  });
}

void brushImage(ClothImage& image, const BrushStroke& stroke) {
  PIXELCLOTH_CHECK(std::isfinite(stroke.radius) && stroke.radius > 0,
                   "brush radius must be > 0 pixels, got " << stroke.radius);
  PIXELCLOTH_CHECK(std::isfinite(stroke.x) && std::isfinite(stroke.y) && std::isfinite(stroke.dn),
                   "brush centre and amount must be finite");
  image.validate();
  const int W = image.width, L = static_cast<int>(image.layers.size());
  PIXELCLOTH_CHECK(stroke.x >= 0 && stroke.x < L * W && stroke.y >= 0 && stroke.y < image.height,
                   "brush centre (" << stroke.x << ", " << stroke.y << ") is outside the " << L * W << " x "
                                    << image.height << " preview");
  const int l = static_cast<int>(stroke.x) / W;
  const double cx = stroke.x - l * W, r = stroke.radius;
  ClothLayer& layer = image.layers[l];
  int x0 = std::max(0, (int)std::floor(cx - r)), x1 = std::min(W - 1, (int)std::ceil(cx + r));
  int y0 = std::max(0, (int)std::floor(stroke.y - r)), y1 = std::min(image.height - 1, (int)std::ceil(stroke.y + r));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      if (layer.mask(y, x) < 0.5f) continue;
      double d2 = ((x - cx) * (x - cx) + (y - stroke.y) * (y - stroke.y)) / (r * r);
      if (d2 >= 1) continue;
      layer.dn(y, x) += static_cast<float>(stroke.dn * (1 - d2) * (1 - d2));
    }
}

void blendImages(ClothImage& image, const ClothImage& other, const Eigen::MatrixXf& alpha) {
  other.validate();
  const std::string name = other.source.empty() ? "second image" : other.source;
  PIXELCLOTH_CHECK(other.width == image.width && other.height == image.height,
                   name << ": is " << other.width << " x " << other.height << ", expected " << image.width << " x "
                        << image.height << " like the image it is blended into");
  std::vector<const ClothLayer*> from;
  for (const ClothLayer& l : image.layers) from.push_back(&other.layer(l.name));
  PIXELCLOTH_CHECK(alpha.size() > 0, "blend: the alpha mask is empty");
  int index = 0;
  std::vector<ClothLayer*> to;
  for (ClothLayer& l : image.layers) to.push_back(&l);
  forEachPixel(image, alpha, [&](ClothLayer& layer, int x, int y, float a) {
    while (to[index] != &layer) ++index;
    const ClothLayer& src = *from[index];
    layer.du(y, x) += a * (src.du(y, x) - layer.du(y, x));
    layer.dv(y, x) += a * (src.dv(y, x) - layer.dv(y, x));
    layer.dn(y, x) += a * (src.dn(y, x) - layer.dn(y, x));
  });
}

Eigen::MatrixXf readEditMask(const std::filesystem::path& path, const ClothImage& image) {
  core::RgbImage png = core::readPng(path);
  const int W = image.width, L = static_cast<int>(image.layers.size());
  PIXELCLOTH_CHECK(png.height == image.height && (png.width == W || png.width == L * W),
                   path.string() << ": mask is " << png.width << " x " << png.height << ", expected " << W << " x "
                                 << image.height
                                 << (L > 1 ? " (every layer) or " + std::to_string(L * W) + " x " +
                                                 std::to_string(image.height) + " (layers side by side)"
                                           : std::string()));
  Eigen::MatrixXf alpha(png.height, png.width);
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const std::uint8_t* p = png.at(x, y);
      alpha(y, x) = (p[0] + p[1] + p[2]) / (3.0f * 255.0f);
    }
  return alpha;
}

}  // namespace pixelcloth::patches
