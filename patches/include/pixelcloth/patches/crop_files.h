#pragma once

// Patch crop files: each patch's enlarged crop of a garment's offsets as one EXR, patch_NN.exr in a folder (channels
// du dv dn and the mask, the crop's frame). They are what a patch decoder predicts (the paper's Sec. 5, one image per
// patch) and what `pixelcloth stitch` assembles into a garment.

#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/cloth_image.h"

namespace pixelcloth::patches {

/// One patch's crop, sampled back onto the garment vertices it covers.
struct PatchCropValues {
  int patch = 0;
  std::vector<int> vertices;  ///< the crop's sample.vertices: garment vertices, sorted
  Eigen::MatrixXf values;     ///< #vertices x 3: du dv dn at those vertices
};

/// The enlarged crop of every patch of `garment`, in patch id order (enlargedCrop of each garmentPatches entry).
std::vector<EnlargedCrop> garmentCrops(const garment::Garment& garment);

/// Writes `folder`/patch_NN.exr for each of `crops` (garmentCrops; the folder is created): `offsets` (#V x 3)
/// rasterised into the crop, with its mask. Each file is written atomically.
void writePatchCrops(const std::filesystem::path& folder, const std::vector<EnlargedCrop>& crops,
                     const Eigen::MatrixXf& offsets);

/// Reads patch_NN.exr of `folder` for every patch of `garment` and samples each back onto the patch's vertices.
/// Throws InputError naming the file for a missing folder or file, a crop of the wrong size or layer count, or values
/// inside the patch that are not finite.
std::vector<PatchCropValues> readPatchCrops(const std::filesystem::path& folder, const garment::Garment& garment);

}  // namespace pixelcloth::patches
