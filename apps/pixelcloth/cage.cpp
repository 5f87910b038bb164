// pixelcloth cage: a garment's cage (seams, openings, body loops, centre lines, splits) and its patches.
#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/viz/pictures.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct CageArgs {
  std::string garment = "tshirt";
  std::string out;
  int size = 512;
};

void runCage(const CageArgs& args) {
  core::checkOutputFolder(args.out);
  core::checkRunFolder(args.out, {"cage.json", {}, "a cage"});
  viz::writeCageFolder(garment::resolveGarment(args.garment, "--garment"), args.out, args.size);
}
}  // namespace

void registerCage(CLI::App& app) {
  auto args = std::make_shared<CageArgs>();
  CLI::App* verb = app.add_subcommand(
      "cage", "Build a garment's cage (seams, openings, body loops, centre lines) and split it into patches");
  verb->add_option("--garment", args->garment, kGarmentHelp)->capture_default_str();
  verb->add_option("--out", args->out,
                   "Output folder: cage.json (curves and nodes), patches.json (per patch: id, side, vertices, ordered "
                   "boundary, bounding box in pixels), cage.png")
      ->required();
  verb->add_option("--size", args->size, "Cloth image size in pixels the patch boxes are measured in and drawn at")
      ->check(CLI::Range(64, 4096))
      ->capture_default_str();
  verb->callback([args] { runCage(*args); });
}

}  // namespace pixelcloth::apps
