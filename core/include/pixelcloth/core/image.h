#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace pixelcloth::core {

/// An 8-bit RGB picture for previews (PNG). Pixel (x, y) with y = 0 the top row.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  ///< width * height * 3, row-major, top row first

  RgbImage() = default;
  RgbImage(int width, int height, std::array<std::uint8_t, 3> fill = {255, 255, 255});

  std::uint8_t* at(int x, int y) { return &pixels[3 * (static_cast<size_t>(y) * width + x)]; }
  const std::uint8_t* at(int x, int y) const { return &pixels[3 * (static_cast<size_t>(y) * width + x)]; }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  void set(int x, int y, std::array<std::uint8_t, 3> color);
  /// Alpha-blends `color` over pixel (x, y); ignores pixels outside the image.
  void blend(int x, int y, std::array<std::uint8_t, 3> color, double alpha);
};

using Color = std::array<std::uint8_t, 3>;

/// Writes an 8-bit RGB PNG through libpng, atomically (temporary name, then rename).
void writePng(const std::filesystem::path& path, const RgbImage& image);

/// Reads an 8-bit RGB or RGBA PNG (alpha dropped). Throws `InputError` naming the file on failure.
RgbImage readPng(const std::filesystem::path& path);

/// Fills the triangle (a, b, c), given in pixel coordinates (x right, y down), with one color.
void fillTriangle(RgbImage& image, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                  Color color);

/// Draws an anti-aliased line of `width` pixels from a to b (pixel coordinates).
void drawLine(RgbImage& image, const Eigen::Vector2d& a, const Eigen::Vector2d& b, Color color, double width = 1.0);

/// Draws a filled disc of `radius` pixels.
void drawDisc(RgbImage& image, const Eigen::Vector2d& center, double radius, Color color);

/// Pastes `source` into `target` with its top-left corner at (x, y).
void paste(RgbImage& target, const RgbImage& source, int x, int y);

/// Writes `text` in a 5x7 pixel bitmap font, each font pixel a `scale` x `scale` block, the top-left corner of the
/// first character at `position` (pixels, x right, y down); characters advance by 6 * scale. Knows digits, letters
/// (upper case drawn as lower case), '_', '-' and '.'; other characters leave a blank. Pixels outside are clipped.
void drawText(RgbImage& image, const Eigen::Vector2i& position, const std::string& text, Color color, int scale = 1);

/// Width and height in pixels of `text` as drawText writes it.
Eigen::Vector2i textExtent(const std::string& text, int scale = 1);

/// A color from a categorical palette of 12 well-separated colors (index taken modulo 12).
Color paletteColor(int index);

}  // namespace pixelcloth::core
