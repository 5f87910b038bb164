#pragma once
// Private to pixelcloth_garment: the checks importGarment applies to a garment read from an OBJ and a cage JSON, run on
// a garment built in memory (the OBJ importer without a cage file, garment/src/obj_import.cpp).

#include <nlohmann/json.hpp>
#include <string>

#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

/// Runs on `garment` exactly the checks importGarment applies (see its comment in garment.h: UVs on every face, no
/// unused vertex, one UV per vertex and layout, no degenerate UV triangle, unique names, polylines along mesh edges,
/// openings along the boundary with the cloth on their left and covering it, layouts meeting only along seams, every
/// patch closed). Throws `InputError` whose message starts with `context` (the file the garment came from) for the
/// first problem; vertices are named as importGarment names them ("vertex 12 (OBJ vertex 13)"). `garment.vertexUV`
/// must be what the faces' UVs and layouts give (an internal error otherwise).
void validateGarment(const Garment& garment, const std::string& context);

/// garment.json's object for `garment`, as saveGarment writes it (and validateGarment checks it).
nlohmann::json garmentJson(const Garment& garment);

}  // namespace pixelcloth::garment
