#pragma once

#include <Eigen/Core>
#include <string>

#include "pixelcloth/core/image.h"

namespace pixelcloth::viz {

/// Fills the triangle (a, b, c), given in pixel coordinates (x right, y down), with one color.
void fillTriangle(core::RgbImage& image, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                  core::Color color);

/// Draws an anti-aliased line of `width` pixels from a to b (pixel coordinates).
void drawLine(core::RgbImage& image, const Eigen::Vector2d& a, const Eigen::Vector2d& b, core::Color color,
              double width = 1.0);

/// Draws a filled disc of `radius` pixels.
void drawDisc(core::RgbImage& image, const Eigen::Vector2d& center, double radius, core::Color color);

/// Pastes `source` into `target` with its top-left corner at (x, y).
void paste(core::RgbImage& target, const core::RgbImage& source, int x, int y);

/// Writes `text` in a 5x7 pixel bitmap font, each font pixel a `scale` x `scale` block, the top-left corner of the
/// first character at `position` (pixels, x right, y down); characters advance by 6 * scale. Knows digits, letters
/// (upper case drawn as lower case), '_', '-' and '.'; other characters leave a blank. Pixels outside are clipped.
void drawText(core::RgbImage& image, const Eigen::Vector2i& position, const std::string& text, core::Color color,
              int scale = 1);

/// Width and height in pixels of `text` as drawText writes it.
Eigen::Vector2i textExtent(const std::string& text, int scale = 1);

/// A color from a categorical palette of 12 well-separated colors (index taken modulo 12).
core::Color paletteColor(int index);

/// An RGB colour of three values in [0, 1] (clamped) as bytes.
core::Color toColor(const Eigen::Vector3d& rgb);

}  // namespace pixelcloth::viz
