#pragma once

#include <Eigen/Core>
#include <filesystem>

#include "pixelcloth/patches/cloth_image.h"

namespace pixelcloth::patches {

// Cloth image editing (paper appendix B): edits act on the offset channels of the non-empty pixels (mask > 0) of
// every layer; masks are never changed. A `region` is an alpha matrix with values in [0, 1]: empty (the default)
// means the whole image; height x width applies to every layer; height x (layers * width) addresses the layers side
// by side, as in the PNG preview of `renderClothImage`.

/// Adds (du, dv) metres, times the region's alpha, to the du and dv channels (moves the cloth along the body).
void shiftImage(ClothImage& image, float du, float dv, const Eigen::MatrixXf& region = {});

/// Inflates or shrinks: dn <- dn + alpha * ((scale - 1) * dn + add), i.e. dn * scale + add where alpha is 1.
void inflateImage(ClothImage& image, float scale, float add = 0, const Eigen::MatrixXf& region = {});

/// A brush stroke on dn: adds dn * (1 - (d / radius)^2)^2 (a smooth bump, C1 at its rim) at pixels within `radius`,
/// d the distance in pixels from the centre. The centre is in preview pixel coordinates (pixel (x, y) of layer l is
/// (l * width + x, y)), so the stroke lies in one layer; at the centre pixel the added value is exactly `dn`.
struct BrushStroke {
  double x = 0, y = 0;  ///< centre, pixels (column, row; fractional allowed)
  double radius = 8;    ///< pixels, > 0
  float dn = 0;         ///< metres added at the centre
};
void brushImage(ClothImage& image, const BrushStroke& stroke);

/// Masked blend: offsets <- (1 - alpha) * image + alpha * other, with `other` of the same size and layers. alpha 0
/// keeps `image`, 1 takes `other`. Throws `InputError` (naming `other.source`) for a size or layer mismatch.
void blendImages(ClothImage& image, const ClothImage& other, const Eigen::MatrixXf& alpha);

/// Reads an alpha region from a PNG: grey level (mean of RGB) / 255. Its size must be width x height or
/// (layers * width) x height of `image`; throws `InputError` naming the file otherwise.
Eigen::MatrixXf readEditMask(const std::filesystem::path& path, const ClothImage& image);

}  // namespace pixelcloth::patches
