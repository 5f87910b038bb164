#pragma once

#include <Eigen/Core>

#include "pixelcloth/garment/garment.h"

namespace pixelcloth::patches {

/// Where a layout's pattern space lands in its cloth image: a square window of pattern space mapped to
/// width x height pixels, u to the right and v up (so v decreases down the rows). Pixel centres sit at
/// integer + 0.5 in pixel coordinates.
struct ImageFrame {
  Eigen::Vector2d topLeft{0, 0};  ///< pattern-space point (metres) at pixel coordinate (0, 0), the top-left corner
  double metresPerPixel = 1.0;
  int width = 0;
  int height = 0;

  /// Pixel coordinates (x right, y down, continuous) of a pattern-space point.
  Eigen::Vector2d toPixel(const Eigen::Vector2d& uv) const {
    return {(uv.x() - topLeft.x()) / metresPerPixel, (topLeft.y() - uv.y()) / metresPerPixel};
  }
  /// Pattern-space point of continuous pixel coordinates.
  Eigen::Vector2d toPattern(const Eigen::Vector2d& pixel) const {
    return {topLeft.x() + pixel.x() * metresPerPixel, topLeft.y() - pixel.y() * metresPerPixel};
  }
  /// Pattern-space point at the centre of pixel (x, y).
  Eigen::Vector2d pixelCentre(int x, int y) const { return toPattern({x + 0.5, y + 0.5}); }
};

/// The default margin of layout frames: the layouts' longer side covers 74% of the image. It sets the cloth a pixel
/// holds (T-shirt at 512 px: 2.16 mm, so a 128 px patch box holds 0.277 m of pattern, enough for the upper-torso
/// patches that span a 0.27 m torso half; at a 3% margin no 14-patch split of the shirt fits 128 px) and leaves
/// room for 16 px of padding around the layout at 256 px.
inline constexpr double kLayoutMargin = 0.13;

/// The frame of one layout in a size x size image: the layout's UV bounding box, centred, its longer side
/// covering (1 - 2 * margin) of the image. The T-shirt's front and back layouts get the same scale (the larger
/// of the two), so a pixel is the same size of cloth on both sides.
ImageFrame layoutFrame(const garment::Garment& garment, int layout, int size, double margin = kLayoutMargin);

}  // namespace pixelcloth::patches
