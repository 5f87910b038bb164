// pixelcloth garment: a garment template as a mesh with pattern-space UVs, and its pattern picture.
#include "pixelcloth/garment/garment.h"

#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/viz/pictures.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct GarmentArgs {
  std::string kind;
  std::string out;
  int vertices = 0;
};

void runGarment(const GarmentArgs& args) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  Garment garment;
  if (args.kind == "tshirt") {
    TShirtOptions options;
    if (args.vertices > 0) options.targetVertices = args.vertices;
    options.validate();
    checkOutputFolder(args.out);
    garment = makeTShirt(options);
  } else {
    NecktieOptions options;
    if (args.vertices > 0) options.targetVertices = args.vertices;
    options.validate();
    checkOutputFolder(args.out);
    garment = makeNecktie(options);
  }
  saveGarment(args.out, garment);
  writePng(std::filesystem::path(args.out) / "pattern.png", renderPattern(garment));
  writePng(std::filesystem::path(args.out) / "garment.png", renderGarmentOnBody(garment, nullptr));
  PIXELCLOTH_INFO("garment: " << garment.summary() << " -> " << args.out
                              << "/{garment.obj, garment.json, pattern.png, garment.png}");
}
}  // namespace

void registerGarment(CLI::App& app) {
  auto args = std::make_shared<GarmentArgs>();
  CLI::App* verb = app.add_subcommand("garment",
                                      "Make a garment template (flat sewing pattern sewn into one mesh) and "
                                      "its pattern picture");
  verb->add_option("kind", args->kind, "Which garment: tshirt or necktie")
      ->required()
      ->check(CLI::IsMember({"tshirt", "necktie"}));
  verb->add_option("--out", args->out, "Output folder (garment.obj with vt, garment.json, pattern.png, garment.png)")
      ->required();
  verb->add_option("--vertices", args->vertices,
                   "Target vertex count (default: 3000 for the T-shirt, 500 for the necktie)")
      ->check(CLI::Range(100, 200000));
  verb->callback([args] { runGarment(*args); });
}

}  // namespace pixelcloth::apps
