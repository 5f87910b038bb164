// The learned worn length of cage curve segments (DESIGN.md, "Key-point-to-cage spline solver"): the lines and their
// file. Fitting lives with the solver (spline_solver.cpp), which knows how markers split each curve into segments.
#include "pixelcloth/cage/length_model.h"

#include <algorithm>
#include <cmath>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"

namespace pixelcloth::cage {

double LengthModel::target(const std::string& curve, double rest, double chord) const {
  auto it = curves.find(curve);
  PIXELCLOTH_CHECK(it != curves.end(), "length model: no line for curve '" << curve << "'");
  const double ratio = it->second.intercept + it->second.slope * chord / rest;
  return std::max(ratio * rest, 1.0001 * chord);
}

void LengthModel::validate(const std::string& garmentName, const Cage& cage, const std::string& context) const {
  PIXELCLOTH_CHECK(garment == garmentName,
                   context << ": the length model is for garment '" << garment << "', not '" << garmentName << "'");
  PIXELCLOTH_CHECK(std::isfinite(markerSpacing) && markerSpacing > 0,
                   context << ": marker spacing " << markerSpacing << ", expected > 0");
  for (const CageCurve& curve : cage.curves) {
    auto it = curves.find(curve.name);
    PIXELCLOTH_CHECK(it != curves.end(), context << ": the length model has no line for curve '" << curve.name << "'");
    PIXELCLOTH_CHECK(std::isfinite(it->second.intercept) && std::isfinite(it->second.slope),
                     context << ": the line of curve '" << curve.name << "' is not finite");
  }
}

void LengthModelOptions::validate() const {
  PIXELCLOTH_CHECK(smoothingPasses >= 0 && smoothingPasses <= 100,
                   "length model: smoothingPasses " << smoothingPasses << ", expected 0 to 100");
  PIXELCLOTH_CHECK(std::isfinite(shrinkage) && shrinkage >= 0,
                   "length model: shrinkage " << shrinkage << ", expected >= 0");
}

nlohmann::json toJson(const LengthModel& model) {
  nlohmann::json curves = nlohmann::json::object();
  for (const auto& [name, line] : model.curves)
    curves[name] = {
        {"intercept", line.intercept}, {"slope", line.slope}, {"segments", line.segments}, {"rms", line.rms}};
  return {{"format", "pixelcloth.length_model"},
          {"version", 1},
          {"garment", model.garment},
          {"marker_spacing_m", model.markerSpacing},
          {"smoothing_passes", model.smoothingPasses},
          {"samples", model.samples},
          {"ratio", "worn length / rest length = intercept + slope * chord / rest length"},
          {"curves", curves}};
}

LengthModel lengthModelFromJson(const nlohmann::json& json, const std::string& context) {
  PIXELCLOTH_CHECK(json.is_object(), context << ": expected a JSON object, found " << json.type_name());
  const std::string format = core::requireValue<std::string>(json, "format", context);
  PIXELCLOTH_CHECK(format == "pixelcloth.length_model",
                   context << ": format '" << format << "', expected 'pixelcloth.length_model'");
  LengthModel model;
  model.garment = core::requireValue<std::string>(json, "garment", context);
  model.markerSpacing = core::requireValue<double>(json, "marker_spacing_m", context);
  model.smoothingPasses = core::requireValue<int>(json, "smoothing_passes", context);
  model.samples = core::requireValue<int>(json, "samples", context);
  const nlohmann::json& curves = core::requireField(json, "curves", context);
  PIXELCLOTH_CHECK(curves.is_object() && !curves.empty(),
                   context << ": field 'curves' is " << curves.dump().substr(0, 40) << ", expected an object of lines");
  for (const auto& [name, item] : curves.items()) {
    const std::string where = context + ": curves." + name;
    PIXELCLOTH_CHECK(item.is_object(), where << " is " << item.type_name() << ", expected an object");
    LengthModel::Line line;
    line.intercept = core::requireValue<double>(item, "intercept", where);
    line.slope = core::requireValue<double>(item, "slope", where);
    line.segments = item.contains("segments") ? core::requireValue<int>(item, "segments", where) : 0;
    line.rms = item.contains("rms") ? core::requireValue<double>(item, "rms", where) : 0.0;
    PIXELCLOTH_CHECK(std::isfinite(line.intercept) && std::isfinite(line.slope),
                     where << ": intercept and slope must be finite numbers");
    model.curves[name] = line;
  }
  return model;
}

LengthModel readLengthModel(const std::filesystem::path& path) {
  return lengthModelFromJson(core::readJson(path), path.string());
}

void writeLengthModel(const std::filesystem::path& path, const LengthModel& model) {
  core::writeJson(path, toJson(model));
}

}  // namespace pixelcloth::cage
