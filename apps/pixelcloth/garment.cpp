// pixelcloth garment: a garment template, or a user's garment imported from an OBJ with UVs and a cage JSON, as a
// garment folder (mesh with pattern-space UVs, layouts and cage) and its pictures.
#include "pixelcloth/garment/garment.h"

#include <memory>
#include <string>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct GarmentArgs {
  std::string kind;       ///< template name, or empty with --import
  std::string importObj;  ///< --import: OBJ with per-corner UVs
  std::string cage;       ///< --cage: layouts and cage of the imported OBJ
  std::string out;
  int vertices = 0;
};

/// Exactly one of a template name or --import; --cage goes with --import, --vertices with a template.
void checkGarmentArgs(const GarmentArgs& args) {
  std::string names;
  for (const std::string& name : garment::templateNames()) names += (names.empty() ? "" : ", ") + name;
  PIXELCLOTH_CHECK(!args.importObj.empty() || args.cage.empty(),
                   "garment: --cage " << args.cage << " only goes with --import OBJ");
  PIXELCLOTH_CHECK(!args.kind.empty() || !args.importObj.empty(),
                   "garment: no garment given; expected a template name (" << names << ") or --import OBJ --cage JSON");
  PIXELCLOTH_CHECK(args.kind.empty() || args.importObj.empty(), "garment: both the template '"
                                                                    << args.kind << "' and --import " << args.importObj
                                                                    << " given; expected one of them");
  PIXELCLOTH_CHECK(args.importObj.empty() || !args.cage.empty(),
                   "garment: --import " << args.importObj
                                        << " needs --cage JSON (layouts, seams, openings and cage lines of the mesh)");
  PIXELCLOTH_CHECK(args.importObj.empty() || args.vertices == 0,
                   "garment: --vertices applies to the templates only; an imported mesh keeps its vertices");
}

void runGarment(const GarmentArgs& args) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  checkGarmentArgs(args);
  Garment garment;
  if (!args.importObj.empty()) {
    checkOutputFolder(args.out);
    // Read and validated in full before anything is written.
    garment = importGarment(args.importObj, args.cage);
  } else if (args.kind == "tshirt") {
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
                                      "Make a garment template (flat sewing pattern sewn into one mesh), or import a "
                                      "garment from an OBJ with UVs and its cage, and draw its pattern");
  verb->add_option("kind", args->kind, "Which template: tshirt or necktie (default: none; give it or --import)")
      ->check(CLI::IsMember(garment::templateNames()));
  verb->add_option("--import", args->importObj,
                   "Import this OBJ (per-corner UVs in pattern-space metres, one layout per face) instead of making a "
                   "template (default: none)");
  verb->add_option("--cage", args->cage,
                   "With --import: JSON with name, layouts, face_layout, panels, seams, openings and cage_lines, in "
                   "garment.json's schema, vertex indices from 0 (default: none; required with --import)");
  verb->add_option("--out", args->out, "Output folder (garment.obj with vt, garment.json, pattern.png, garment.png)")
      ->required();
  verb->add_option("--vertices", args->vertices,
                   "Target vertex count of a template (default: 3000 for the T-shirt, 500 for the necktie)")
      ->check(CLI::Range(100, 200000));
  verb->callback([args] { runGarment(*args); });
}

}  // namespace pixelcloth::apps
