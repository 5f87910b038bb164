// pixelcloth garment: a garment template, or a user's garment imported from an OBJ with UVs (its cage found
// automatically, or read from a cage JSON), as a garment folder (mesh with pattern-space UVs, layouts and cage) and its
// pictures.
#include "pixelcloth/garment/garment.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/garment/obj_import.h"
#include "pixelcloth/patches/body_fit.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct GarmentArgs {
  std::string kind;               ///< template name, or empty with --import
  std::string importObj;          ///< --import: OBJ with per-corner UVs
  std::string cage;               ///< --cage: layouts and cage of the imported OBJ (empty: found automatically)
  std::string name;               ///< --name of an imported garment without --cage (empty: the OBJ's file stem)
  std::string up = "y";           ///< --up: the OBJ's up axis
  double scale = 1.0;             ///< --scale: positions multiplied by this
  std::vector<double> translate;  ///< --translate X Y Z, metres (empty: none)
  std::string out;
  int vertices = 0;
  std::string size;    ///< --size XS..XXL of a template (sizeGrade)
  double grade = 1.0;  ///< --grade F of a template
  std::string fitTo;   ///< --fit-to: body folder (or "mannequin") to place the cage lines from (empty: none)
};

/// Exactly one of a template name or --import; --cage, --name and the placement options go with --import, --vertices
/// with a template.
void checkGarmentArgs(const GarmentArgs& args, bool placementGiven) {
  std::string names;
  for (const std::string& name : garment::templateNames()) names += (names.empty() ? "" : ", ") + name;
  PIXELCLOTH_CHECK(!args.importObj.empty() || args.cage.empty(),
                   "garment: --cage " << args.cage << " only goes with --import OBJ");
  PIXELCLOTH_CHECK(!args.kind.empty() || !args.importObj.empty(),
                   "garment: no garment given; expected a template name (" << names << ") or --import OBJ");
  PIXELCLOTH_CHECK(args.kind.empty() || args.importObj.empty(), "garment: both the template '"
                                                                    << args.kind << "' and --import " << args.importObj
                                                                    << " given; expected one of them");
  PIXELCLOTH_CHECK(args.importObj.empty() || args.vertices == 0,
                   "garment: --vertices applies to the templates only; an imported mesh keeps its vertices");
  PIXELCLOTH_CHECK(args.importObj.empty() || (args.size.empty() && args.grade == 1.0),
                   "garment: --size and --grade grade a template; an imported garment keeps its size");
  PIXELCLOTH_CHECK(args.size.empty() || args.grade == 1.0, "garment: --size " << args.size << " and --grade "
                                                                            << args.grade << " given; expected one");
  PIXELCLOTH_CHECK(!args.importObj.empty() || args.fitTo.empty(),
                   "garment: --fit-to places the cage lines of an imported OBJ; a template has its own");
  PIXELCLOTH_CHECK(!args.importObj.empty() || !placementGiven,
                   "garment: --up, --scale and --translate place an imported OBJ; they only go with --import OBJ");
  PIXELCLOTH_CHECK(args.cage.empty() || args.name.empty(),
                   "garment: --name " << args.name << " names a garment imported without --cage; with --cage "
                                      << args.cage << " the name is its field 'name'");
}

void runGarment(const GarmentArgs& args, bool placementGiven) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  checkGarmentArgs(args, placementGiven);
  Garment garment;
  if (!args.importObj.empty()) {
    ObjImportOptions placement;
    placement.name = args.name;
    placement.up = args.up.empty() ? ' ' : args.up[0];
    placement.scale = args.scale;
    if (!args.translate.empty())
      placement.translate = Eigen::Vector3d(args.translate[0], args.translate[1], args.translate[2]);
    placement.validate();
    checkOutputFolder(args.out);
    checkRunFolder(args.out, {"garment.json", {}, "a garment"});
    // Read and validated in full before anything is written.
    if (args.cage.empty()) {
      ObjImportReport report;
      garment = importGarmentObj(args.importObj, placement, &report);
      for (const std::string& note : report.notes) PIXELCLOTH_INFO("garment: " << args.importObj << ": " << note);
    } else {
      garment = importGarment(args.importObj, args.cage);
      placeGarment(garment, placement);
    }
    if (!args.fitTo.empty()) {
      // The body is read before anything is written; a folder of that name wins over the built-in mannequin.
      const bool builtIn = args.fitTo == "mannequin" && !std::filesystem::exists(args.fitTo);
      if (builtIn) PIXELCLOTH_INFO("garment: meshing the built-in mannequin");
      const Body body = builtIn ? makeMannequin() : loadBody(args.fitTo);
      const patches::BodyFitReport fit = patches::fitGarmentToBody(garment, body);
      PIXELCLOTH_INFO("garment: fitted to " << args.fitTo << ": " << fit.summary());
    }
  } else {
    TemplateRequest request;
    request.vertices = args.vertices;
    request.grade = !args.size.empty() ? sizeGrade(args.size) : args.grade;
    const std::string context = "garment " + args.kind;
    if (request.grade != 1.0) templateTraits(args.kind, context);  // an unknown name fails before the folder check
    checkOutputFolder(args.out);
    checkRunFolder(args.out, {"garment.json", {}, "a garment"});
    garment = makeGarment(args.kind, request, context);
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
  CLI::App* verb = app.add_subcommand(
      "garment",
      "Make a garment template (flat sewing pattern sewn into one mesh), or import a garment OBJ with UVs (layouts, "
      "panels, seams and openings found from its UV islands and groups, or read from a cage JSON), and draw its "
      "pattern");
  verb->add_option("kind", args->kind, "Which template: tshirt or necktie (default: none; give it or --import)")
      ->check(CLI::IsMember(garment::templateNames()));
  verb->add_option("--import", args->importObj,
                   "Import this OBJ instead of making a template: positions and per-corner UVs (vt; several per vertex "
                   "along seams), optionally g/o/usemtl groups per pattern piece; UV islands become layouts, groups "
                   "(else islands) panels, the edges between panels seams, the boundary loops openings, named by where "
                   "they sit; normalised or atlas UVs are rescaled to metres of cloth (default: none)");
  verb->add_option("--cage", args->cage,
                   "With --import: JSON with name, layouts, face_layout, panels, seams, openings and cage_lines, in "
                   "garment.json's schema, vertex indices from 0, instead of finding them (default: none, found "
                   "automatically)");
  verb->add_option("--name", args->name,
                   "With --import and no --cage: the garment's name (default: the OBJ's file name without extension)");
  CLI::Option* up =
      verb->add_option("--up", args->up,
                       "With --import: the OBJ's up axis; a Z-up file (body facing -Y) is turned to Y up, "
                       "body facing +Z (default: y)")
          ->check(CLI::IsMember({"y", "z"}));
  CLI::Option* scale =
      verb->add_option("--scale", args->scale,
                       "With --import: multiply the OBJ's positions by S after turning them, e.g. 0.01 for a file in "
                       "centimetres (default: 1)")
          ->check(CLI::PositiveNumber);
  CLI::Option* translate = verb->add_option("--translate", args->translate,
                                            "X Y Z: with --import, then add this to the positions, metres (default: "
                                            "0 0 0)")
                               ->expected(3);
  verb->add_option("--fit-to", args->fitTo,
                   "With --import: a body folder from 'pixelcloth body' (or 'mannequin', the built-in one) to fit the "
                   "garment to: its neckline is aligned to the body's, and the chest, waist and bicep loops, centre "
                   "lines and side-panel splits are placed where the body's cage meets the garment dressed on it and "
                   "cut into the mesh; patches larger than 128 px of a 512 px image are split, so that per-patch models "
                   "can train on it (default: none; the garment keeps one patch per pattern piece)");
  verb->add_option("--out", args->out, "Output folder (garment.obj with vt, garment.json, pattern.png, garment.png)")
      ->required();
  verb->add_option("--vertices", args->vertices,
                   "Target vertex count of a template (default: 3000 for the T-shirt, 500 for the necktie)")
      ->check(CLI::Range(100, 200000));
  verb->add_option("--size", args->size,
                   "T-shirt size XS, S, M, L, XL or XXL: the pattern graded by 0.88 to 1.18, M being the default "
                   "(default: M)");
  verb->add_option("--grade", args->grade,
                   "T-shirt pattern graded by F (every pattern length times F; 1: the default size M), 0.6 to 1.6; "
                   "`dress` names the grade a body needs (default: 1)")
      ->check(CLI::Range(0.6, 1.6));
  verb->callback([args, up, scale, translate] {
    runGarment(*args, up->count() > 0 || scale->count() > 0 || translate->count() > 0);
  });
}

}  // namespace pixelcloth::apps
