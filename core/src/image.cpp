#include "pixelcloth/core/image.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

RgbImage::RgbImage(int w, int h, Color fill) : width(w), height(h), pixels(static_cast<size_t>(w) * h * 3) {
  PIXELCLOTH_CHECK(w > 0 && h > 0, "image size must be positive, got " << w << " x " << h);
  for (size_t i = 0; i < pixels.size(); i += 3) {
    pixels[i] = fill[0];
    pixels[i + 1] = fill[1];
    pixels[i + 2] = fill[2];
  }
}

void RgbImage::set(int x, int y, Color color) {
  if (!contains(x, y)) return;
  std::uint8_t* p = at(x, y);
  p[0] = color[0];
  p[1] = color[1];
  p[2] = color[2];
}

void RgbImage::blend(int x, int y, Color color, double alpha) {
  if (!contains(x, y) || alpha <= 0) return;
  alpha = std::min(alpha, 1.0);
  std::uint8_t* p = at(x, y);
  for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(std::lround(p[k] * (1 - alpha) + color[k] * alpha));
}

namespace {
// libpng reports through these; our own messages (with the file name) replace its stderr output.
void pngError(png_structp png, png_const_charp) { png_longjmp(png, 1); }
void pngWarning(png_structp, png_const_charp) {}

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};

}  // namespace

void writePng(const std::filesystem::path& path, const RgbImage& image) {
  PIXELCLOTH_CHECK(
      image.width > 0 && image.height > 0 && image.pixels.size() == static_cast<size_t>(image.width) * image.height * 3,
      path.string() << ": refusing to write an empty or inconsistent image");
  writeAtomically(path, [&](const std::filesystem::path& temporary) {
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(temporary.c_str(), "wb"));
    PIXELCLOTH_CHECK(file, path.string() << ": cannot open for writing");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, pngError, pngWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    PIXELCLOTH_CHECK(png && info, path.string() << ": libpng could not start");
    if (setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      PIXELCLOTH_FAIL(path.string() << ": libpng failed while writing");
    }
    png_init_io(png, file.get());
    png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y) png_write_row(png, const_cast<png_bytep>(image.at(0, y)));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    PIXELCLOTH_CHECK(std::fflush(file.get()) == 0, path.string() << ": write failed (disk full?)");
  });
}

RgbImage readPng(const std::filesystem::path& path) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  PIXELCLOTH_CHECK(file, path.string() << ": no such file or not readable");
  png_byte signature[8] = {};
  PIXELCLOTH_CHECK(std::fread(signature, 1, 8, file.get()) == 8 && png_sig_cmp(signature, 0, 8) == 0,
                   path.string() << ": not a PNG file (bad signature)");
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, pngError, pngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  PIXELCLOTH_CHECK(png && info, path.string() << ": libpng could not start");
  RgbImage image;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    PIXELCLOTH_FAIL(path.string() << ": corrupted or truncated PNG");
  }
  png_init_io(png, file.get());
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  png_set_strip_16(png);
  png_set_palette_to_rgb(png);
  png_set_gray_to_rgb(png);
  png_set_strip_alpha(png);
  png_read_update_info(png, info);
  int width = static_cast<int>(png_get_image_width(png, info));
  int height = static_cast<int>(png_get_image_height(png, info));
  image = RgbImage(width, height);
  for (int y = 0; y < height; ++y) png_read_row(png, image.at(0, y), nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

}  // namespace pixelcloth::core
