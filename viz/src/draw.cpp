// Drawing on RgbImage: triangles, anti-aliased lines, discs, a 5x7 bitmap font, a categorical palette.
#include "pixelcloth/viz/draw.h"

#include <algorithm>
#include <cmath>

#include "pixelcloth/core/error.h"

namespace pixelcloth::viz {

using core::Color;
using core::RgbImage;

namespace {

/// 5x7 bitmap glyphs, one byte per row (top first), bit 4 the leftmost column.
struct Glyph {
  char character;
  std::uint8_t rows[7];
};
const Glyph kFont[] = {
    {'0', {0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110}},
    {'1', {0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110}},
    {'2', {0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b01000, 0b11111}},
    {'3', {0b11111, 0b00010, 0b00100, 0b00010, 0b00001, 0b10001, 0b01110}},
    {'4', {0b00010, 0b00110, 0b01010, 0b10010, 0b11111, 0b00010, 0b00010}},
    {'5', {0b11111, 0b10000, 0b11110, 0b00001, 0b00001, 0b10001, 0b01110}},
    {'6', {0b00110, 0b01000, 0b10000, 0b11110, 0b10001, 0b10001, 0b01110}},
    {'7', {0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b01000, 0b01000}},
    {'8', {0b01110, 0b10001, 0b10001, 0b01110, 0b10001, 0b10001, 0b01110}},
    {'9', {0b01110, 0b10001, 0b10001, 0b01111, 0b00001, 0b00010, 0b01100}},
    {'a', {0b00000, 0b00000, 0b01110, 0b00001, 0b01111, 0b10001, 0b01111}},
    {'b', {0b10000, 0b10000, 0b10110, 0b11001, 0b10001, 0b10001, 0b11110}},
    {'c', {0b00000, 0b00000, 0b01110, 0b10000, 0b10000, 0b10001, 0b01110}},
    {'d', {0b00001, 0b00001, 0b01101, 0b10011, 0b10001, 0b10001, 0b01111}},
    {'e', {0b00000, 0b00000, 0b01110, 0b10001, 0b11111, 0b10000, 0b01110}},
    {'f', {0b00110, 0b01001, 0b01000, 0b11100, 0b01000, 0b01000, 0b01000}},
    {'g', {0b00000, 0b01111, 0b10001, 0b10001, 0b01111, 0b00001, 0b01110}},
    {'h', {0b10000, 0b10000, 0b10110, 0b11001, 0b10001, 0b10001, 0b10001}},
    {'i', {0b00100, 0b00000, 0b01100, 0b00100, 0b00100, 0b00100, 0b01110}},
    {'j', {0b00010, 0b00000, 0b00110, 0b00010, 0b00010, 0b10010, 0b01100}},
    {'k', {0b10000, 0b10000, 0b10010, 0b10100, 0b11000, 0b10100, 0b10010}},
    {'l', {0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110}},
    {'m', {0b00000, 0b00000, 0b11010, 0b10101, 0b10101, 0b10001, 0b10001}},
    {'n', {0b00000, 0b00000, 0b10110, 0b11001, 0b10001, 0b10001, 0b10001}},
    {'o', {0b00000, 0b00000, 0b01110, 0b10001, 0b10001, 0b10001, 0b01110}},
    {'p', {0b00000, 0b00000, 0b11110, 0b10001, 0b11110, 0b10000, 0b10000}},
    {'q', {0b00000, 0b00000, 0b01101, 0b10011, 0b01111, 0b00001, 0b00001}},
    {'r', {0b00000, 0b00000, 0b10110, 0b11001, 0b10000, 0b10000, 0b10000}},
    {'s', {0b00000, 0b00000, 0b01110, 0b10000, 0b01110, 0b00001, 0b11110}},
    {'t', {0b01000, 0b01000, 0b11100, 0b01000, 0b01000, 0b01001, 0b00110}},
    {'u', {0b00000, 0b00000, 0b10001, 0b10001, 0b10001, 0b10011, 0b01101}},
    {'v', {0b00000, 0b00000, 0b10001, 0b10001, 0b10001, 0b01010, 0b00100}},
    {'w', {0b00000, 0b00000, 0b10001, 0b10001, 0b10101, 0b10101, 0b01010}},
    {'x', {0b00000, 0b00000, 0b10001, 0b01010, 0b00100, 0b01010, 0b10001}},
    {'y', {0b00000, 0b00000, 0b10001, 0b10001, 0b01111, 0b00001, 0b01110}},
    {'z', {0b00000, 0b00000, 0b11111, 0b00010, 0b00100, 0b01000, 0b11111}},
    {'_', {0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b11111}},
    {'-', {0b00000, 0b00000, 0b00000, 0b11111, 0b00000, 0b00000, 0b00000}},
    {'.', {0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b01100, 0b01100}},
    {',', {0b00000, 0b00000, 0b00000, 0b00000, 0b01100, 0b00100, 0b01000}},
    {':', {0b00000, 0b01100, 0b01100, 0b00000, 0b01100, 0b01100, 0b00000}},
    {'(', {0b00010, 0b00100, 0b01000, 0b01000, 0b01000, 0b00100, 0b00010}},
    {')', {0b01000, 0b00100, 0b00010, 0b00010, 0b00010, 0b00100, 0b01000}},
    {'/', {0b00001, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0b10000}},
    {'%', {0b11000, 0b11001, 0b00010, 0b00100, 0b01000, 0b10011, 0b00011}},
    {'+', {0b00000, 0b00100, 0b00100, 0b11111, 0b00100, 0b00100, 0b00000}},
    {'=', {0b00000, 0b00000, 0b11111, 0b00000, 0b11111, 0b00000, 0b00000}},
};

const Glyph* findGlyph(char c) {
  if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  for (const Glyph& glyph : kFont)
    if (glyph.character == c) return &glyph;
  return nullptr;
}

}  // namespace

void fillTriangle(RgbImage& image, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                  Color color) {
  int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
  int x1 = std::min(image.width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
  int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
  int y1 = std::min(image.height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
  auto edge = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
  };
  double area = edge(a, b, c);
  if (area == 0) return;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      Eigen::Vector2d p(x + 0.5, y + 0.5);
      double w0 = edge(b, c, p) / area, w1 = edge(c, a, p) / area, w2 = edge(a, b, p) / area;
      if (w0 >= 0 && w1 >= 0 && w2 >= 0) image.set(x, y, color);
    }
  }
}

void drawLine(RgbImage& image, const Eigen::Vector2d& a, const Eigen::Vector2d& b, Color color, double width) {
  // Coverage from the distance of each pixel centre to the segment, with a one-pixel soft edge.
  double half = 0.5 * width;
  int x0 = static_cast<int>(std::floor(std::min(a.x(), b.x()) - half - 1));
  int x1 = static_cast<int>(std::ceil(std::max(a.x(), b.x()) + half + 1));
  int y0 = static_cast<int>(std::floor(std::min(a.y(), b.y()) - half - 1));
  int y1 = static_cast<int>(std::ceil(std::max(a.y(), b.y()) + half + 1));
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, image.width - 1);
  y1 = std::min(y1, image.height - 1);
  Eigen::Vector2d d = b - a;
  double len2 = d.squaredNorm();
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      Eigen::Vector2d p(x + 0.5, y + 0.5);
      double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
      double dist = (p - (a + t * d)).norm();
      image.blend(x, y, color, std::clamp(half + 0.5 - dist, 0.0, 1.0));
    }
  }
}

void drawDisc(RgbImage& image, const Eigen::Vector2d& center, double radius, Color color) {
  for (int y = static_cast<int>(center.y() - radius - 1); y <= static_cast<int>(center.y() + radius + 1); ++y) {
    for (int x = static_cast<int>(center.x() - radius - 1); x <= static_cast<int>(center.x() + radius + 1); ++x) {
      double dist = (Eigen::Vector2d(x + 0.5, y + 0.5) - center).norm();
      image.blend(x, y, color, std::clamp(radius + 0.5 - dist, 0.0, 1.0));
    }
  }
}

void paste(RgbImage& target, const RgbImage& source, int x, int y) {
  for (int j = 0; j < source.height; ++j) {
    for (int i = 0; i < source.width; ++i) {
      const std::uint8_t* p = source.at(i, j);
      target.set(x + i, y + j, {p[0], p[1], p[2]});
    }
  }
}

Color paletteColor(int index) {
  static const Color kPalette[12] = {{31, 119, 180},  {255, 127, 14}, {44, 160, 44},   {214, 39, 40},
                                     {148, 103, 189}, {140, 86, 75},  {227, 119, 194}, {127, 127, 127},
                                     {188, 189, 34},  {23, 190, 207}, {174, 199, 232}, {255, 187, 120}};
  return kPalette[((index % 12) + 12) % 12];
}

Eigen::Vector2i textExtent(const std::string& text, int scale) {
  if (text.empty()) return {0, 0};
  return {(6 * static_cast<int>(text.size()) - 1) * scale, 7 * scale};
}

void drawText(RgbImage& image, const Eigen::Vector2i& position, const std::string& text, Color color, int scale) {
  PIXELCLOTH_CHECK(scale >= 1 && scale <= 64, "drawText: scale must be in [1, 64], got " << scale);
  for (size_t i = 0; i < text.size(); ++i) {
    const Glyph* glyph = findGlyph(text[i]);
    if (!glyph) continue;
    const int left = position.x() + 6 * scale * static_cast<int>(i);
    for (int row = 0; row < 7; ++row) {
      for (int column = 0; column < 5; ++column) {
        if (!(glyph->rows[row] & (0x10 >> column))) continue;
        for (int dy = 0; dy < scale; ++dy) {
          for (int dx = 0; dx < scale; ++dx) {
            const int x = left + column * scale + dx, y = position.y() + row * scale + dy;
            if (image.contains(x, y)) image.set(x, y, color);
          }
        }
      }
    }
  }
}

core::Color toColor(const Eigen::Vector3d& rgb) {
  core::Color out;
  for (int i = 0; i < 3; ++i) out[i] = static_cast<std::uint8_t>(std::lround(255 * std::clamp(rgb[i], 0.0, 1.0)));
  return out;
}

}  // namespace pixelcloth::viz
