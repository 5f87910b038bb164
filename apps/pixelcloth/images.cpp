// pixelcloth images: per-vertex offsets <-> whole-garment cloth images (EXR + PNG preview).
#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/garment.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/patches/cloth_image.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct ImagesArgs {
  std::string garment;
  std::string values;
  std::string image;
  std::string out;
  int width = 0;
  int height = 0;
  int padding = 16;
};

void runImages(const ImagesArgs& args) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::patches;
  PIXELCLOTH_CHECK(args.values.empty() != args.image.empty(), "images: give exactly one of --values and --image");
  ClothImageOptions options;
  options.width = args.width;
  options.height = args.height;
  options.padding = args.padding;
  options.validate();
  if (!args.values.empty()) checkOutputFolder(args.out);
  Garment garment = args.garment == "tshirt" ? makeTShirt() : makeNecktie();
  ClothImager imager(garment, options);
  if (!args.values.empty()) {
    Eigen::MatrixXf offsets = readNpyMatrixF(args.values, garment.mesh.numVertices(), 3);
    ClothImage image = imager.rasterize(offsets);
    std::filesystem::path folder(args.out);
    writeClothImage(folder / "cloth.exr", image);
    writePng(folder / "cloth.png", renderClothImage(image));
    PIXELCLOTH_INFO("images: " << garment.mesh.numVertices() << " vertices -> " << imager.width() << " x "
                               << imager.height() << " x " << image.layers.size() << " layers -> " << args.out
                               << "/{cloth.exr, cloth.png}");
  } else {
    ClothImage image = readClothImage(args.image);
    Eigen::MatrixXf offsets = imager.sample(image);
    writeNpy(args.out, offsets);
    PIXELCLOTH_INFO("images: " << args.image << " -> " << offsets.rows() << " x 3 offsets -> " << args.out);
  }
}
}  // namespace

void registerImages(CLI::App& app) {
  auto args = std::make_shared<ImagesArgs>();
  CLI::App* verb = app.add_subcommand(
      "images",
      "Per-vertex offsets (float32 NPY, #V x 3: du dv dn) to a cloth image (EXR + PNG preview), or a cloth image back "
      "to per-vertex offsets");
  verb->add_option("--garment", args->garment, "Garment template: tshirt or necktie (built with default options)")
      ->required()
      ->check(CLI::IsMember({"tshirt", "necktie"}));
  verb->add_option("--values", args->values, "Per-vertex offsets to rasterise: float32 NPY of shape (#V, 3)");
  verb->add_option("--image", args->image, "Cloth image (EXR) to sample back to per-vertex offsets");
  verb->add_option("--out", args->out,
                   "With --values: output folder (cloth.exr, cloth.png); with --image: output NPY file (#V, 3)")
      ->required();
  verb->add_option("--width", args->width, "Image width in pixels (default 0: 256 for the T-shirt, 64 for the necktie)")
      ->check(CLI::Range(0, 8192));
  verb->add_option("--height", args->height, "Image height in pixels (default 0: 256)")->check(CLI::Range(0, 8192));
  verb->add_option("--padding", args->padding, "Padding around each layout in pixels (default 16)")
      ->check(CLI::Range(0, 4096));
  verb->callback([args] { runImages(*args); });
}

}  // namespace pixelcloth::apps
