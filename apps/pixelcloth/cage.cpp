// pixelcloth cage: a garment template's cage (seams, openings, body loops, centre lines, splits) and its patches.
#include <memory>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/viz/patch_picture.h"
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
  writeCageFolder(args.garment == "tshirt" ? garment::makeTShirt() : garment::makeNecktie(), args.out, args.size);
}
}  // namespace

void writeCageFolder(const garment::Garment& garment, const std::filesystem::path& out, int size) {
  const cage::Cage cage = cage::garmentCage(garment);
  const std::vector<patches::Patch> patchList = patches::segmentPatches(garment, cage::cutEdges(cage));

  nlohmann::json cageJson = cage::toJson(cage);
  cageJson["garment"] = garment.name;
  core::writeJson(out / "cage.json", cageJson);

  nlohmann::json list = nlohmann::json::array();
  double largest = 0;
  for (const patches::Patch& patch : patchList) {
    const Eigen::Vector2d extent = patches::patchPixelExtent(garment, patch, size);
    largest = std::max(largest, extent.maxCoeff());
    list.push_back({{"id", patch.id},
                    {"side", garment.layouts[patch.layout]},
                    {"vertices", patch.vertices},
                    {"boundary", patch.boundary},
                    {"bbox_px_" + std::to_string(size), {extent.x(), extent.y()}}});
  }
  core::writeJson(out / "patches.json", {{"garment", garment.name}, {"image_size", size}, {"patches", list}});

  std::vector<viz::PictureCurve> curves;
  for (const cage::CageCurve& curve : cage.curves)
    curves.push_back({curve.vertices, curve.closed, cage::curveKindName(curve.kind)});
  core::writePng(out / "cage.png", viz::renderPatches(garment, patchList, curves, size));
  PIXELCLOTH_INFO("cage: " << garment.name << ": " << cage.curves.size() << " curves, " << cage.nodes.size()
                           << " nodes, " << patchList.size() << " patches, largest patch " << largest << " px of "
                           << size << " -> " << out.string() << "/{cage.json, patches.json, cage.png}");
}

void registerCage(CLI::App& app) {
  auto args = std::make_shared<CageArgs>();
  CLI::App* verb = app.add_subcommand(
      "cage", "Build a garment template's cage (seams, openings, body loops, centre lines) and split it into patches");
  verb->add_option("--garment", args->garment, "Which garment: tshirt or necktie")
      ->check(CLI::IsMember({"tshirt", "necktie"}))
      ->capture_default_str();
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
