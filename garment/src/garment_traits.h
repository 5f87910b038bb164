#pragma once

// garment.json's "traits" field, shared by the garment-folder reader and writer.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

/// The traits a garment.json gives: its "traits" field; when absent (folders written before garments carried their
/// traits) those of the template named by its "name" field, and the defaults for any other name.
GarmentTraits traitsOfGarmentJson(const nlohmann::json& root, const core::Mesh& mesh, const std::string& file);

/// The traits of the template called `name` for its mesh `mesh` (the necktie's pins are its knot vertices), the
/// defaults for any other name: what a garment folder without "traits" meant when it was written.
GarmentTraits legacyTemplateTraits(const std::string& name, const core::Mesh& mesh);

/// {"name": "tshirt" | "necktie", "options": {every field}}: what Garment::recipe holds for a template built with
/// these options.
nlohmann::json recipeOf(const TShirtOptions& options);
nlohmann::json recipeOf(const NecktieOptions& options);

/// The template a garment folder's "template" recipe ({"name", "options"}, as Garment::recipe) describes, built anew.
/// Throws `InputError` prefixed with `context` for an unknown template or options out of range.
Garment rebuildTemplate(const nlohmann::json& recipe, const std::string& context);

/// The necktie's knot end: vertices within 4 cm of the top of `mesh` (Y up), held at the neck by the simulation.
std::vector<int> necktieKnotVertices(const core::Mesh& mesh);

}  // namespace pixelcloth::garment
