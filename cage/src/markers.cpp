// Marker sets on a garment's cage: definition, placement from ground truth (noise, dropout), JSON files.
#include "pixelcloth/cage/markers.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "pixelcloth/cage/geodesic.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"

namespace pixelcloth::cage {

void MarkerOptions::validate() const {
  PIXELCLOTH_CHECK(std::isfinite(spacing) && spacing >= 0.01 && spacing <= 10,
                   "markers: spacing " << spacing << " m is out of range, expected 0.01 to 10");
}

void CaptureOptions::validate() const {
  PIXELCLOTH_CHECK(std::isfinite(noise) && noise >= 0, "markers: noise " << noise << " m, expected >= 0");
  PIXELCLOTH_CHECK(std::isfinite(dropout) && dropout >= 0 && dropout < 1,
                   "markers: dropout " << dropout << ", expected a fraction in [0, 1)");
}

void MarkerSet::validate(const garment::Garment& garment, const Cage& cage, const std::string& context,
                         bool requirePositions) const {
  PIXELCLOTH_CHECK(this->garment == garment.name, context << ": markers are for the garment '" << this->garment
                                                          << "', expected '" << garment.name << "'");
  PIXELCLOTH_CHECK(!markers.empty(), context << ": no markers");
  std::set<std::string> names;
  const int n = garment.mesh.numVertices();
  for (size_t i = 0; i < markers.size(); ++i) {
    const Marker& m = markers[i];
    const std::string where = context + ": marker " + std::to_string(i) + " '" + m.name + "'";
    PIXELCLOTH_CHECK(names.insert(m.name).second, where << ": the name is used twice");
    PIXELCLOTH_CHECK(m.vertex >= 0 && m.vertex < n,
                     where << ": vertex " << m.vertex << " is out of range, the " << garment.name << " has " << n);
    PIXELCLOTH_CHECK(m.curve.empty() != m.node.empty(), where << ": expected exactly one of 'curve' and 'node'");
    if (!m.curve.empty()) {
      const CageCurve* curve = cage.findCurve(m.curve);
      PIXELCLOTH_CHECK(curve != nullptr, where << ": unknown curve '" << m.curve << "' (the " << garment.name
                                               << " cage has e.g. '" << cage.curves.front().name << "')");
      PIXELCLOTH_CHECK(std::find(curve->vertices.begin(), curve->vertices.end(), m.vertex) != curve->vertices.end(),
                       where << ": vertex " << m.vertex << " is not on curve '" << m.curve << "'");
    } else {
      PIXELCLOTH_CHECK(cage.findNode(m.node) >= 0, where << ": unknown node '" << m.node << "'");
      bool found = false;  // node names may repeat (see defineMarkers): any node of that name at that vertex
      for (const CageNode& node : cage.nodes) found = found || (node.name == m.node && node.vertex == m.vertex);
      PIXELCLOTH_CHECK(found, where << ": vertex " << m.vertex << " is not node '" << m.node << "' (vertex "
                                    << cage.nodes[cage.findNode(m.node)].vertex << ")");
    }
    const bool anyNaN = m.position.array().isNaN().all();
    PIXELCLOTH_CHECK(m.hasPosition() || (anyNaN && !requirePositions),
                     where << ": " << (anyNaN ? "no position" : "position is not finite") << ", expected [x, y, z] in "
                           << "metres");
  }
}

MarkerSet defineMarkers(const garment::Garment& garment, const Cage& cage, const MarkerOptions& options) {
  options.validate();
  MarkerSet set;
  set.garment = garment.name;
  std::set<int> nodeVertices;
  std::set<std::string> names;
  for (const CageNode& node : cage.nodes) {
    // Node names repeat where two curves meet twice (a necktie band crosses the outline at both edges).
    const std::string name = names.insert(node.name).second ? node.name : node.name + "@" + std::to_string(node.vertex);
    names.insert(name);
    set.markers.push_back({name, node.vertex, "", node.name});
    nodeVertices.insert(node.vertex);
  }
  std::set<int> used = nodeVertices;
  for (const CageCurve& curve : cage.curves) {
    const int n = static_cast<int>(curve.vertices.size());
    const std::vector<double> s = patternArcLengths(garment, curve);
    std::vector<int> stops;  // curve indices of the nodes on the curve, in order
    for (int i = 0; i < n; ++i)
      if (nodeVertices.count(curve.vertices[i])) stops.push_back(i);
    if (stops.empty()) stops.push_back(0);
    // A closed curve needs at least three markers for its spline: add points to its gaps when it has fewer nodes.
    const int atLeast = curve.closed ? std::max(0, 3 - static_cast<int>(stops.size())) : 0;
    const int perGapAtLeast =
        curve.closed ? (atLeast + static_cast<int>(stops.size()) - 1) / static_cast<int>(stops.size()) : 0;
    if (curve.closed) stops.push_back(stops.front() + n);  // around the loop back to the first stop
    int count = 0;
    for (size_t k = 0; k + 1 < stops.size(); ++k) {
      // Arc length of curve index i (i may run past n on a closed curve).
      auto arc = [&](int i) { return i < n ? s[i] : s[n] + s[i - n]; };
      const double s0 = arc(stops[k]), s1 = arc(stops[k + 1]);
      const int inserted = std::max(perGapAtLeast, static_cast<int>(std::lround((s1 - s0) / options.spacing)) - 1);
      for (int j = 1; j <= inserted; ++j) {
        const double target = s0 + (s1 - s0) * j / (inserted + 1);
        int best = stops[k];
        for (int i = stops[k]; i <= stops[k + 1]; ++i)
          if (std::abs(arc(i) - target) < std::abs(arc(best) - target)) best = i;
        const int vertex = curve.vertices[best % n];
        if (!used.insert(vertex).second) continue;
        set.markers.push_back({curve.name + ":" + std::to_string(count++), vertex, curve.name, ""});
      }
    }
  }
  return set;
}

MarkerSet placeMarkers(const MarkerSet& definition, const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                       const CaptureOptions& options) {
  options.validate();
  std::mt19937_64 random(options.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  MarkerSet out;
  out.garment = definition.garment;
  for (const Marker& m : definition.markers) {
    PIXELCLOTH_CHECK(m.vertex >= 0 && m.vertex < positions.rows(), "markers: marker '" << m.name << "' uses vertex "
                                                                                       << m.vertex << ", but there are "
                                                                                       << positions.rows());
    // Draw both numbers for every marker so that the noise of a marker does not depend on the dropout.
    const double drop = uniform(random);
    Eigen::Vector3d noise(gauss(random), gauss(random), gauss(random));
    if (m.node.empty() && drop < options.dropout) continue;
    Marker placed = m;
    placed.position = positions.row(m.vertex).transpose() + options.noise * noise;
    out.markers.push_back(placed);
  }
  return out;
}

nlohmann::json toJson(const MarkerSet& markers) {
  nlohmann::json list = nlohmann::json::array();
  for (const Marker& m : markers.markers) {
    nlohmann::json item = {{"name", m.name}, {"vertex", m.vertex}};
    if (!m.curve.empty()) item["curve"] = m.curve;
    if (!m.node.empty()) item["node"] = m.node;
    if (m.hasPosition()) item["position"] = {m.position.x(), m.position.y(), m.position.z()};
    list.push_back(item);
  }
  return {{"format", "pixelcloth.markers"}, {"version", 1}, {"garment", markers.garment}, {"markers", list}};
}

MarkerSet markersFromJson(const nlohmann::json& json, const std::string& context) {
  MarkerSet set;
  PIXELCLOTH_CHECK(json.is_object(), context << ": expected a JSON object {format, garment, markers}");
  if (json.contains("format")) {  // written by pixelcloth; a hand-made file may leave it out
    const std::string format = core::requireValue<std::string>(json, "format", context);
    PIXELCLOTH_CHECK(format == "pixelcloth.markers",
                     context << ": format '" << format << "', expected 'pixelcloth.markers' (a markers file)");
  }
  set.garment = core::requireValue<std::string>(json, "garment", context);
  const nlohmann::json& list = core::requireField(json, "markers", context);
  PIXELCLOTH_CHECK(list.is_array(), context << ": field 'markers' is " << list.type_name() << ", expected an array");
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = context + ": markers[" + std::to_string(i) + "]";
    const nlohmann::json& item = list[i];
    PIXELCLOTH_CHECK(item.is_object(), where << " is " << item.type_name() << ", expected an object");
    Marker m;
    m.name = core::requireValue<std::string>(item, "name", where);
    m.vertex = core::requireValue<int>(item, "vertex", where);
    if (item.contains("curve")) m.curve = core::requireValue<std::string>(item, "curve", where);
    if (item.contains("node")) m.node = core::requireValue<std::string>(item, "node", where);
    if (item.contains("position")) {
      const nlohmann::json& p = item["position"];
      PIXELCLOTH_CHECK(p.is_array() && p.size() == 3,
                       where << " '" << m.name << "': field 'position' is " << p.dump() << ", expected [x, y, z]");
      for (int k = 0; k < 3; ++k) {
        // JSON has no NaN: nlohmann writes it as null, and people write strings; both are refused here.
        PIXELCLOTH_CHECK(p[k].is_number() && std::isfinite(p[k].get<double>()),
                         where << " '" << m.name << "': position " << p.dump() << " is not three finite numbers");
        m.position[k] = p[k].get<double>();
      }
    }
    set.markers.push_back(m);
  }
  return set;
}

MarkerSet readMarkers(const std::filesystem::path& path) {
  return markersFromJson(core::readJson(path), path.string());
}

void writeMarkers(const std::filesystem::path& path, const MarkerSet& markers) {
  core::writeJson(path, toJson(markers));
}

}  // namespace pixelcloth::cage
