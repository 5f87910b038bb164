// The built-in garment templates, chosen by name in one place, and what a --garment argument names.
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "garment_traits.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

namespace fs = std::filesystem;

namespace {

/// The fields of each template's options, by the names garment.json's "template" recipe gives them.
template <typename Options>
struct Field {
  const char* name;
  double Options::*real = nullptr;
  int Options::*integer = nullptr;
};

const std::vector<Field<TShirtOptions>>& tshirtFields() {
  using O = TShirtOptions;
  static const std::vector<Field<O>> fields = {
      {"target_vertices", nullptr, &O::targetVertices}, {"length", &O::length},
      {"half_width", &O::halfWidth},                    {"shoulder_half_width", &O::shoulderHalfWidth},
      {"shoulder_drop", &O::shoulderDrop},              {"armpit_depth", &O::armpitDepth},
      {"sleeve_length", &O::sleeveLength},              {"sleeve_hem_height", &O::sleeveHemHeight},
      {"neck_half_width", &O::neckHalfWidth},           {"front_neck_depth", &O::frontNeckDepth},
      {"back_neck_depth", &O::backNeckDepth},           {"neck_side_height", &O::neckSideHeight},
      {"torso_depth", &O::torsoDepth},                  {"chest_height", &O::chestHeight},
      {"waist_height", &O::waistHeight},                {"side_panel_x", &O::sidePanelX},
      {"bicep_fraction", &O::bicepFraction},            {"sleeve_depth", &O::sleeveDepth},
      {"boundary_spacing", &O::boundarySpacing}};
  return fields;
}

const std::vector<Field<NecktieOptions>>& necktieFields() {
  using O = NecktieOptions;
  static const std::vector<Field<O>> fields = {
      {"target_vertices", nullptr, &O::targetVertices}, {"length", &O::length}, {"knot_width", &O::knotWidth},
      {"blade_width", &O::bladeWidth},   {"tip_height", &O::tipHeight},      {"top_height", &O::topHeight},
      {"front_offset", &O::frontOffset}, {"boundary_spacing", &O::boundarySpacing},
      {"bands", nullptr, &O::bands}};
  return fields;
}

template <typename Options>
nlohmann::json recipe(const char* name, const Options& options, const std::vector<Field<Options>>& fields) {
  nlohmann::json values = nlohmann::json::object();
  for (const Field<Options>& f : fields) {
    if (f.real) values[f.name] = options.*f.real;
    else values[f.name] = options.*f.integer;
  }
  return {{"name", name}, {"options", values}};
}

/// Options from a recipe's "options": every field present (a recipe is written whole), then validated.
template <typename Options>
Options optionsOf(const nlohmann::json& values, const std::vector<Field<Options>>& fields, const std::string& context) {
  PIXELCLOTH_CHECK(values.is_object(), context << ": options: expected a JSON object, found " << values.type_name());
  Options options;
  for (const Field<Options>& f : fields) {
    if (f.real) options.*f.real = core::requireValue<double>(values, f.name, context + ": options");
    else options.*f.integer = core::requireValue<int>(values, f.name, context + ": options");
  }
  options.validate();
  return options;
}

std::string knownTemplates() {
  std::string known;
  for (const std::string& n : templateNames()) known += (known.empty() ? "" : ", ") + n;
  return known;
}
}  // namespace

const std::vector<std::string>& templateNames() {
  static const std::vector<std::string> names = {"tshirt", "necktie"};
  return names;
}

Garment makeGarment(const std::string& name, const std::string& context) {
  return makeGarment(name, TemplateRequest{}, context);
}

Garment makeGarment(const std::string& name, const TemplateRequest& request, const std::string& context) {
  if (name == "tshirt") {
    TShirtOptions options = TShirtOptions{}.graded(request.grade);
    if (request.vertices > 0) options.targetVertices = request.vertices;
    options.validate();
    return makeTShirt(options);
  }
  if (name == "necktie") {
    PIXELCLOTH_CHECK(request.grade == 1.0, context << ": the necktie comes in one size; --size and --grade grade the "
                                                      "T-shirt");
    NecktieOptions options;
    if (request.vertices > 0) options.targetVertices = request.vertices;
    options.validate();
    return makeNecktie(options);
  }
  PIXELCLOTH_FAIL(context << ": unknown garment template '" << name << "'; expected one of: " << knownTemplates());
}

GarmentTraits templateTraits(const std::string& name, const std::string& context) {
  if (name == "tshirt") return GarmentTraits{};
  if (name == "necktie") {
    // Paper section 6: the tie hangs from the neck (centre-line joints only), its images are 64 x 256, its offsets
    // are learnt in the root frame with the edge-length loss, and its knot end is held.
    GarmentTraits traits;
    traits.poseJoints = 4;
    traits.imageWidth = 64;
    traits.imageHeight = 256;
    traits.rootFrameOffsets = true;
    traits.normalLossWeight = 0.1;
    traits.edgeLossWeight = 0.1;
    return traits;
  }
  PIXELCLOTH_FAIL(context << ": unknown garment template '" << name << "'; expected one of: " << knownTemplates());
}

nlohmann::json recipeOf(const TShirtOptions& options) { return recipe("tshirt", options, tshirtFields()); }
nlohmann::json recipeOf(const NecktieOptions& options) { return recipe("necktie", options, necktieFields()); }

Garment rebuildTemplate(const nlohmann::json& recipe, const std::string& context) {
  PIXELCLOTH_CHECK(recipe.is_object(), context << ": expected a JSON object, found " << recipe.type_name());
  const auto name = core::requireValue<std::string>(recipe, "name", context);
  const nlohmann::json& values = core::requireField(recipe, "options", context);
  if (name == "tshirt") return makeTShirt(optionsOf<TShirtOptions>(values, tshirtFields(), context));
  if (name == "necktie") return makeNecktie(optionsOf<NecktieOptions>(values, necktieFields(), context));
  PIXELCLOTH_FAIL(context << ": unknown garment template '" << name << "'; expected one of: " << knownTemplates());
}

GarmentTraits legacyTemplateTraits(const std::string& name, const core::Mesh& mesh) {
  if (name == "necktie") {
    GarmentTraits traits = templateTraits(name);
    traits.pinned = necktieKnotVertices(mesh);
    return traits;
  }
  return GarmentTraits{};
}

Garment resolveGarment(const std::string& nameOrFolder, const std::string& context) {
  std::error_code ec;
  const fs::path path(nameOrFolder);
  bool isTemplate = false;
  for (const std::string& name : templateNames()) isTemplate = isTemplate || name == nameOrFolder;
  const bool garmentFolder =
      fs::is_regular_file(path / "garment.json", ec) && fs::is_regular_file(path / "garment.obj", ec);
  if (isTemplate && !garmentFolder) return makeGarment(nameOrFolder, context);  // a stray folder of that name aside
  if (!nameOrFolder.empty() && fs::exists(path, ec)) {
    PIXELCLOTH_CHECK(fs::is_directory(path, ec),
                     context << " " << nameOrFolder
                             << ": a file, not a garment folder; expected a template name (" << knownTemplates()
                             << ") or a folder holding garment.obj and garment.json (from `pixelcloth garment`)");
    PIXELCLOTH_CHECK(fs::exists(path / "garment.json", ec) && fs::exists(path / "garment.obj", ec),
                     context << " " << nameOrFolder
                             << ": the folder holds no garment.obj and garment.json; expected a garment folder "
                                "as `pixelcloth garment` writes it (a template's --out or --import's)");
    return loadGarment(path);
  }
  PIXELCLOTH_FAIL(context << " '" << nameOrFolder << "' is neither a garment template (" << knownTemplates()
                          << ") nor an existing garment folder (garment.obj + garment.json from `pixelcloth garment`)");
}

}  // namespace pixelcloth::garment
