#include "pixelcloth/patches/crop_files.h"

#include <cstdio>
#include <string>

#include "pixelcloth/core/error.h"
#include "pixelcloth/patches/patch.h"

namespace pixelcloth::patches {

namespace fs = std::filesystem;

namespace {
fs::path cropPath(const fs::path& folder, int patch) {
  char name[32];
  std::snprintf(name, sizeof(name), "patch_%02d.exr", patch);
  return folder / name;
}
/// The crop's own mask says which pixels it covers: a crop of another garment's patch (or of another patch) leaves
/// pixels of this one empty.
void checkCropMask(const Eigen::MatrixXf& mask, const EnlargedCrop& crop, const fs::path& path, int patch,
                   const std::string& garment) {
  const Eigen::MatrixXf expected = crop.raster.maskImage();
  int uncovered = 0, inside = 0;
  for (Eigen::Index i = 0; i < expected.size(); ++i)
    if (expected(i) >= 2) {
      ++inside;
      if (!(mask(i) >= 1)) ++uncovered;
    }
  PIXELCLOTH_CHECK(uncovered == 0, path.string() << ": its mask leaves " << uncovered << " of the " << inside
                                                 << " pixels of patch " << patch << " of the " << garment
                                                 << " empty: a crop of another garment or patch?");
}

}  // namespace

std::vector<EnlargedCrop> garmentCrops(const garment::Garment& garment) {
  std::vector<EnlargedCrop> crops;
  for (const Patch& patch : garmentPatches(garment)) crops.push_back(enlargedCrop(garment, patch));
  return crops;
}

void writePatchCrops(const fs::path& folder, const std::vector<EnlargedCrop>& crops, const Eigen::MatrixXf& offsets) {
  fs::create_directories(folder);
  for (size_t id = 0; id < crops.size(); ++id) {
    const EnlargedCrop& crop = crops[id];
    const Eigen::MatrixXf pixels = crop.raster.apply(offsets);
    ClothImage image;
    image.width = crop.frame.width;
    image.height = crop.frame.height;
    ClothLayer layer;
    layer.du = toImage(pixels.col(0), image.width, image.height);
    layer.dv = toImage(pixels.col(1), image.width, image.height);
    layer.dn = toImage(pixels.col(2), image.width, image.height);
    layer.mask = crop.raster.maskImage();
    image.layers.push_back(std::move(layer));
    writeClothImage(cropPath(folder, static_cast<int>(id)), image);
  }
}

std::vector<PatchCropValues> readPatchCrops(const fs::path& folder, const garment::Garment& garment) {
  PIXELCLOTH_CHECK(fs::is_directory(folder), folder.string() << ": not a folder (expected patch_00.exr ... one per "
                                                                "patch, each the patch's enlarged crop with channels "
                                                                "du dv dn)");
  std::vector<PatchCropValues> out;
  const std::vector<Patch> all = garmentPatches(garment);
  for (const Patch& patch : all) {
    const fs::path path = cropPath(folder, patch.id);
    PIXELCLOTH_CHECK(fs::is_regular_file(path), path.string()
                                                    << ": missing; the " << garment.name << " needs " << all.size()
                                                    << " crops, patch_00.exr to patch_" << (all.size() - 1) << ".exr");
    const ClothImage image = readClothImage(path);
    const EnlargedCrop crop = enlargedCrop(garment, patch);
    PIXELCLOTH_CHECK(image.layers.size() == 1 && image.width == crop.frame.width && image.height == crop.frame.height,
                     path.string() << ": " << image.width << " x " << image.height << " with " << image.layers.size()
                                   << " layer(s), expected one " << crop.frame.width << " x " << crop.frame.height
                                   << " crop (channels du dv dn, as images --crops writes)");
    const ClothLayer& layer = image.layers.front();
    checkCropMask(layer.mask, crop, path, patch.id, garment.name);
    Eigen::MatrixXf pixels(static_cast<Eigen::Index>(image.width) * image.height, 3);
    pixels << fromImage(layer.du), fromImage(layer.dv), fromImage(layer.dn);
    const Eigen::MatrixXf sampled = crop.sample.apply(pixels);
    PatchCropValues p;
    p.patch = patch.id;
    p.vertices = crop.sample.vertices;
    p.values.resize(static_cast<Eigen::Index>(p.vertices.size()), 3);
    for (size_t i = 0; i < p.vertices.size(); ++i)
      p.values.row(static_cast<Eigen::Index>(i)) = sampled.row(p.vertices[i]);
    PIXELCLOTH_CHECK(p.values.allFinite(), path.string() << ": values that are not finite (NaN or infinity) inside "
                                                            "the patch");
    out.push_back(std::move(p));
  }
  // More crops than patches: crops of a garment with more of them.
  const fs::path extra = cropPath(folder, static_cast<int>(all.size()));
  PIXELCLOTH_CHECK(!fs::exists(extra), extra.string() << ": the " << garment.name << " has " << all.size()
                                                      << " patches (patch_00.exr to patch_" << (all.size() - 1)
                                                      << ".exr); these crops are of another garment");
  return out;
}

}  // namespace pixelcloth::patches
