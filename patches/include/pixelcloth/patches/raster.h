#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/frame.h"

namespace pixelcloth::patches {

/// A sparse linear map between cloth pixels (garment vertices) and image pixels. Pixel index = y * width + x
/// (row-major, top row first), so a column of an applied result reshapes to (height, width) in NumPy.
using SparseOperator = Eigen::SparseMatrix<float, Eigen::RowMajor, int>;

/// What an image pixel is to the garment (the mask channel of a cloth image stores these values as floats).
enum class PixelClass : std::uint8_t {
  Empty = 0,    ///< farther than the padding from the layout: the operator's row is empty
  Padding = 1,  ///< outside the layout, within the padding: the value at the closest point of the layout
  Inside = 2,   ///< centre inside a triangle of the layout: the triangle's barycentric interpolation
};

/// Options of the raster operator.
struct RasterOptions {
  int padding = 16;  ///< pixels outside the layout up to this distance (pixels, centre to layout) get padding values
  /// Throws `InputError` for a negative padding.
  void validate() const;
};

/// Rasterisation of per-vertex values onto the image grid of one layout (paper section 4, "cloth images"):
/// image = matrix * values. Build once, apply many times.
struct RasterOperator {
  ImageFrame frame;                ///< where the layout's pattern space lands in the image
  int layout = 0;                  ///< index into Garment::layouts
  SparseOperator matrix;           ///< (width * height) x #V; rows of inside pixels have 3 entries, padding rows 1 or 2
  std::vector<std::uint8_t> mask;  ///< width * height PixelClass values, same pixel order as the rows
  std::vector<int> vertices;       ///< garment vertices of the rasterised faces, sorted (the only non-empty columns)

  /// `matrix` repacked for a fast `apply` (rows of at most 3 entries as fixed-size triples, runs of non-empty rows);
  /// `buildRaster` and `loadRasterOperator` fill it. Call `pack()` again after changing `matrix`.
  struct Packed {
    struct Row {
      int vertex[3];
      float weight[3];
    };
    std::vector<Row> rows;                     ///< one per non-empty row of `matrix`, in order
    std::vector<std::pair<int, int>> runs;     ///< [first, last + 1) ranges of non-empty rows
    Eigen::Index numRows = -1, nonZeros = -1;  ///< of the matrix it was packed from
  } packed;
  /// Refreshes `packed` from `matrix` (left empty when a row has more than 3 entries: `apply` then uses `matrix`).
  void pack();

  /// image = matrix * values: `values` #V x k (float), result (width * height) x k. Empty pixels are 0.
  Eigen::MatrixXf apply(const Eigen::Ref<const Eigen::MatrixXf>& values) const;
  /// Same, into a preallocated `out` (resized when needed): no allocation when `out` already has the size.
  void applyTo(const Eigen::Ref<const Eigen::MatrixXf>& values, Eigen::MatrixXf& out) const;
  /// Number of pixels of one class.
  int count(PixelClass pixelClass) const;
  /// The mask as a height x width float image (0 empty, 1 padding, 2 inside).
  Eigen::MatrixXf maskImage() const;
};

/// Builds the raster operator of `layout` of `garment` in `frame`: a pixel whose centre lies in a layout triangle
/// (per-corner UVs `mesh.FUV`) gets that triangle's barycentric weights on its 3 garment vertices; a pixel outside
/// the layout but within `options.padding` pixels of it gets the weights of the closest point of the layout (on the
/// closest boundary edge), so images continue smoothly past the boundary; other pixels get empty rows. Per-triangle
/// bounding-box scan for inside pixels, per-boundary-edge scan of nearby pixels for padding. Throws `InputError` for a
/// bad layout, an empty frame, or bad options.
RasterOperator buildRaster(const garment::Garment& garment, int layout, const ImageFrame& frame,
                           const RasterOptions& options = {});

/// Same, restricted to a subset of the layout's faces (a patch): padding is measured from the subset's boundary.
RasterOperator buildRaster(const garment::Garment& garment, int layout, const std::vector<int>& faces,
                           const ImageFrame& frame, const RasterOptions& options = {});

/// Bilinear sampling of an image at the cloth pixels of one layout: values = matrix * image.
struct SampleOperator {
  ImageFrame frame;           ///< the image grid it samples
  int layout = 0;             ///< index into Garment::layouts
  SparseOperator matrix;      ///< #V x (width * height); vertices not in `vertices` have empty rows
  std::vector<int> vertices;  ///< garment vertices it samples, sorted

  /// values = matrix * image: `image` (width * height) x k (float), result #V x k.
  Eigen::MatrixXf apply(const Eigen::Ref<const Eigen::MatrixXf>& image) const;
};

/// The sample operator that inverts `raster`: each of its vertices is interpolated bilinearly between the 4 pixel
/// centres around its UV in that layout, using only pixels that are not empty in `raster.mask` (weights renormalised).
///
/// Round trip sample(raster(x)) on the default T-shirt (makeTShirt(), 2989 vertices), padding 16, default frame margin,
/// both layouts, max |error| over the layout's vertices relative to the field's range there
/// (tests/patches/raster_test.cpp, measured):
///   field                      | 256 x 256: taps inside / all | 512 x 512: taps inside / all
///   linear 0.3u - 0.2v         | 4.4e-8 / 1.3e-3              | 4.4e-8 / 7.3e-4
///   quadratic 2u^2 + uv - v^2  | 1.1e-4 / 2.7e-3              | 5.7e-5 / 1.4e-3
///   sin(10u) cos(10v)          | 1.7e-3 / 3.0e-3              | 8.4e-4 / 2.1e-3
/// "taps inside": vertices whose 4 bilinear pixels are all inside (linear fields exact to float precision there);
/// "all" adds boundary vertices, whose taps include padding pixels holding the closest boundary value rather than the
/// field's extension (an error of up to ~0.5 px times the gradient).
SampleOperator buildSample(const garment::Garment& garment, const RasterOperator& raster);

/// A (width * height) pixel column as a height x width image, and back.
Eigen::MatrixXf toImage(const Eigen::Ref<const Eigen::VectorXf>& pixels, int width, int height);
Eigen::VectorXf fromImage(const Eigen::MatrixXf& image);

/// Writes an operator (frame, layout, sparse matrix, mask, vertices) to one binary file with a checksum, atomically.
void saveOperator(const std::filesystem::path& path, const RasterOperator& raster);
void saveOperator(const std::filesystem::path& path, const SampleOperator& sample);
/// Reads an operator written by `saveOperator`. Throws `InputError` naming the file when it is missing, of the other
/// kind, truncated or corrupted (bad magic, checksum mismatch, indices out of range).
RasterOperator loadRasterOperator(const std::filesystem::path& path);
SampleOperator loadSampleOperator(const std::filesystem::path& path);

}  // namespace pixelcloth::patches
