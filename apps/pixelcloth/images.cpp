// pixelcloth images: per-vertex offsets <-> whole-garment cloth images (EXR + PNG preview).
#include <cstdio>
#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/cloth_image.h"
#include "pixelcloth/patches/crop_files.h"
#include "pixelcloth/viz/pictures.h"
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
  std::string dataset;
  std::vector<int> samples;
  bool all = false;
  bool crops = false;
};

/// Cloth images of dataset samples: cloth_NNNNNN.exr and .png per sample index.
void runDatasetImages(const ImagesArgs& args, const patches::ClothImageOptions& options) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  PIXELCLOTH_CHECK(args.values.empty() && args.image.empty(),
                   "images: --dataset takes the offsets from the dataset; leave out --values and --image");
  PIXELCLOTH_CHECK(args.garment.empty(), "images: --garment " << args.garment << " with --dataset " << args.dataset
                                                              << ": a dataset carries its garment; leave out --garment");
  PIXELCLOTH_CHECK(args.all != !args.samples.empty(), "images: with --dataset give --samples i,j,... or --all");
  checkOutputFolder(args.out);
  checkRunFolder(args.out, {"", {}, "cloth images"});
  const data::Dataset dataset = data::openDataset(datasetFolder(args.dataset));
  const data::DatasetSettings& settings = dataset.info.settings;
  std::vector<int> indices = args.samples;
  if (args.all)
    for (int row = 0; row < dataset.rows(); ++row) indices.push_back(settings.first() + row);
  for (int index : indices) dataset.info.rowOfSample(index, "images: --samples");
  const Garment garment = data::datasetGarment(dataset.info);
  const patches::ClothImager imager(garment, options);
  const std::filesystem::path folder(args.out);
  std::vector<patches::EnlargedCrop> crops;
  if (args.crops) crops = patches::garmentCrops(garment);
  Progress progress("images", static_cast<std::int64_t>(indices.size()));
  for (int index : indices) {
    char name[32];
    std::snprintf(name, sizeof(name), "cloth_%06d", index);
    const patches::ClothImage image = imager.rasterize(dataset.offsetsOf(index - settings.first()));
    patches::writeClothImage(folder / (std::string(name) + ".exr"), image);
    writePng(folder / (std::string(name) + ".png"), viz::renderClothImage(image));
    if (args.crops) {
      std::snprintf(name, sizeof(name), "crops_%06d", index);
      patches::writePatchCrops(folder / name, crops, dataset.offsetsOf(index - settings.first()));
    }
    progress.advance();
  }
  progress.finish();
  PIXELCLOTH_INFO("images: " << indices.size() << " samples of " << args.dataset << " -> " << args.out
                             << "/cloth_NNNNNN.{exr,png}" << (args.crops ? ", crops_NNNNNN/patch_NN.exr" : ""));
}

void runImages(const ImagesArgs& args) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  using namespace pixelcloth::patches;
  ClothImageOptions options;
  options.width = args.width;
  options.height = args.height;
  options.padding = args.padding;
  options.validate();
  PIXELCLOTH_CHECK(!args.crops || !args.dataset.empty(), "images: --crops goes with --dataset");
  if (!args.dataset.empty()) return runDatasetImages(args, options);
  PIXELCLOTH_CHECK(!args.garment.empty(), "images: --garment is required (unless --dataset gives it)");
  PIXELCLOTH_CHECK(args.values.empty() != args.image.empty(),
                   "images: give exactly one of --values, --image and --dataset");
  if (!args.values.empty()) {
    checkOutputFolder(args.out);
    checkRunFolder(args.out, {"", {}, "a cloth image"});
  }
  Garment garment = resolveGarment(args.garment, "--garment");
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
      "to per-vertex offsets, or the samples of a dataset to cloth images");
  verb->add_option("--garment", args->garment,
                   std::string(kGarmentHelp) + "; required unless --dataset, which carries its garment");
  verb->add_option("--values", args->values, "Per-vertex offsets to rasterise: float32 NPY of shape (#V, 3)");
  verb->add_option("--image", args->image, "Cloth image (EXR) to sample back to per-vertex offsets");
  verb->add_option("--dataset", args->dataset,
                   "Dataset folder: write cloth images of its samples (--samples or --all) from its offsets");
  verb->add_option("--samples", args->samples, "With --dataset: sample indices, e.g. 0,5,17")->delimiter(',');
  verb->add_flag("--all", args->all, "With --dataset: every sample of the dataset");
  verb->add_flag("--crops", args->crops,
                 "With --dataset: also each patch's 160 x 160 crop, crops_NNNNNN/patch_NN.exr (what a patch decoder "
                 "predicts and pixelcloth stitch reads)");
  verb->add_option("--out", args->out,
                   "With --values: output folder (cloth.exr, cloth.png); with --image: output NPY file (#V, 3); with "
                   "--dataset: output folder (cloth_NNNNNN.exr and .png per sample)")
      ->required();
  verb->add_option("--width", args->width,
                   "Image width in pixels (default 0: the garment's, 256 for the T-shirt, 64 for the necktie)")
      ->check(CLI::Range(0, 8192));
  verb->add_option("--height", args->height, "Image height in pixels (default 0: the garment's, 256)")
      ->check(CLI::Range(0, 8192));
  verb->add_option("--padding", args->padding, "Padding around each layout in pixels (default 16)")
      ->check(CLI::Range(0, 4096));
  verb->callback([args] { runImages(*args); });
}

}  // namespace pixelcloth::apps
