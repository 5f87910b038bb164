#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "pixelcloth/core/exr_io.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/frame.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/patches/raster.h"

namespace pixelcloth::patches {

/// One layout's part of a cloth image: offsets (du, dv, dn) in metres and the padded mask, each height x width
/// (row 0 the top row, as in `core::ExrImage`).
struct ClothLayer {
  std::string name;  ///< layout name ("front", "back", "tie"); "" for an image read with unprefixed channels
  Eigen::MatrixXf du, dv, dn;
  Eigen::MatrixXf mask;  ///< PixelClass values as floats: 0 empty, 1 padding, 2 inside
};

/// A cloth image (paper section 4): per layout the offsets rasterised on the pattern-space grid, plus the mask.
/// T-shirt: layers front and back (6 offset channels); necktie: layer tie.
struct ClothImage {
  int width = 0;
  int height = 0;
  std::vector<ClothLayer> layers;
  std::string source;  ///< file it was read from, for messages; empty when built in memory

  /// The layer called `name`; throws `InputError` naming `source` and the layers present.
  const ClothLayer& layer(const std::string& name) const;
  ClothLayer& layer(const std::string& name);
  /// As an EXR image: channels "<layer>.du", "<layer>.dv", "<layer>.dn", "<layer>.mask" per layer.
  core::ExrImage toExr() const;
  /// From an EXR image with channels "<layer>.du|dv|dn|mask" (layers found by their ".du" channels), or unprefixed
  /// "du dv dn mask" (one layer named ""). Throws `InputError` naming the file for a missing channel or no layer.
  static ClothImage fromExr(const core::ExrImage& image);
  /// Throws `InputError` (naming `source`) unless every channel of every layer is height x width.
  void validate() const;
};

/// Writes a cloth image as a float32 EXR (`toExr`), atomically.
void writeClothImage(const std::filesystem::path& path, const ClothImage& image);
/// Reads a cloth image from an EXR file; throws `InputError` naming the file when it is missing, corrupted, or lacks a
/// channel.
ClothImage readClothImage(const std::filesystem::path& path);

/// The frame of one layout in a width x height cloth image (non-square allowed, e.g. the necktie's 64 x 256): every
/// layout of the garment at the same scale, the largest at which each layout's UV box fits inside (1 - 2 * margin) of
/// both image dimensions, centred. For width == height this is `layoutFrame(garment, layout, size, margin)`.
ImageFrame clothImageFrame(const garment::Garment& garment, int layout, int width, int height,
                           double margin = kLayoutMargin);

/// Options of whole-garment cloth images.
struct ClothImageOptions {
  int width = 0;                  ///< pixels; 0: the garment's (GarmentTraits::imageWidth: T-shirt 256, necktie 64)
  int height = 0;                 ///< pixels; 0: the garment's (GarmentTraits::imageHeight: 256 for both)
  int padding = 16;               ///< pixels of padding around each layout
  double margin = kLayoutMargin;  ///< fraction of the image left free around the layouts
  /// Throws `InputError` naming the field for out-of-range values.
  void validate() const;
};

/// Whole-garment cloth images: one raster and one sample operator per layout, built once (paper section 4).
class ClothImager {
 public:
  /// Builds the operators of every layout of `garment`.
  explicit ClothImager(const garment::Garment& garment, const ClothImageOptions& options = {});

  /// Cloth image of per-vertex offsets: `offsets` #V x 3 (du, dv, dn), metres. Throws `InputError` for a wrong shape.
  ClothImage rasterize(const Eigen::Ref<const Eigen::MatrixXf>& offsets) const;
  /// Per-vertex offsets #V x 3 from a cloth image of this garment: each vertex sampled bilinearly in the layout(s) it
  /// belongs to, seam vertices (in two layouts) averaged. Throws `InputError` naming `image.source` for a size or
  /// layer mismatch.
  Eigen::MatrixXf sample(const ClothImage& image) const;

  int width() const { return width_; }
  int height() const { return height_; }
  int numVertices() const { return numVertices_; }
  const std::vector<std::string>& layouts() const { return layouts_; }
  const RasterOperator& raster(int layout) const { return rasters_.at(layout); }
  const SampleOperator& sampler(int layout) const { return samplers_.at(layout); }

 private:
  int width_ = 0, height_ = 0, numVertices_ = 0;
  std::string garmentName_;
  std::vector<std::string> layouts_;
  std::vector<RasterOperator> rasters_;
  std::vector<SampleOperator> samplers_;
  Eigen::VectorXf layoutsPerVertex_;  ///< #V: how many layouts each vertex belongs to
};

/// A patch's training image: a crop of the 512 x 512 image of its layout (paper section 4: 160 x 160 crops centred on
/// the patch, loss on the patch plus 16 px of padding).
struct PatchCrop {
  ImageFrame frame;        ///< crop x crop pixels, same metres per pixel as the full image, aligned with its grid
  Eigen::Vector2i origin;  ///< the crop's top-left pixel in the full image (may be negative or past its edge)
  RasterOperator raster;   ///< the patch's faces only: mask = its own triangles (2) + padding (1); columns are garment
                           ///< vertices, non-zero only for the patch's vertices
};

/// The crop of `patch`: centred on the patch's UV bounding box in the `imageSize` frame of its layout (`layoutFrame`),
/// `cropSize` pixels square, and the raster operator of the patch's faces in it. Throws `InputError` for bad sizes.
PatchCrop cropFrame(const garment::Garment& garment, const Patch& patch, int imageSize = 512, int cropSize = 160,
                    const RasterOptions& options = {});

/// The enlarged patch whose crop a patch decoder predicts (DESIGN.md, "Stitching"): the faces of the patch's layout
/// whose three corners lie within `context` pixels of `frame` (a crop of the 512 x 512 image) of a corner of the patch.
/// It holds the patch and about two rings of its neighbours (16 px at 512: 2.3 cm on the T-shirt), so neighbouring
/// patches predict the vertices around the cage curve between them. Sorted.
std::vector<int> enlargedPatchFaces(const garment::Garment& garment, const Patch& patch, const ImageFrame& frame,
                                    double context = 16);

/// What a patch decoder's 160 x 160 image holds (the learning targets and `pixelcloth stitch` read it the same way): the
/// enlarged patch's faces rasterised in the patch's crop with 4 px of padding, and the operator that samples the
/// image back to the vertices it covers.
struct EnlargedCrop {
  ImageFrame frame;        ///< the crop (cropFrame)
  std::vector<int> faces;  ///< enlargedPatchFaces
  RasterOperator raster;
  SampleOperator sample;   ///< sample.vertices: the garment vertices the decoder predicts, sorted
};
EnlargedCrop enlargedCrop(const garment::Garment& garment, const Patch& patch);

}  // namespace pixelcloth::patches
