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

}  // namespace pixelcloth::core
