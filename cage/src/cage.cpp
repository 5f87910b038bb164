#include "pixelcloth/cage/cage.h"

#include <algorithm>
#include <map>
#include <set>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"

namespace pixelcloth::cage {

const CageCurve* Cage::findCurve(const std::string& name) const {
  for (const CageCurve& c : curves)
    if (c.name == name) return &c;
  return nullptr;
}

int Cage::findNode(const std::string& name) const {
  for (size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].name == name) return static_cast<int>(i);
  return -1;
}

std::vector<std::pair<int, int>> Cage::edges() const {
  std::set<std::pair<int, int>> unique;
  for (const CageCurve& c : curves) {
    const size_t n = c.vertices.size();
    for (size_t i = 0; i + 1 < n || (c.closed && i < n && n > 2); ++i) {
      int a = c.vertices[i], b = c.vertices[(i + 1) % n];
      unique.insert(std::minmax(a, b));
    }
  }
  return {unique.begin(), unique.end()};
}

void Cage::validate(const Eigen::MatrixX3i& F, int numVertices, const std::string& context) const {
  std::set<std::pair<int, int>> meshEdges;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) meshEdges.insert(std::minmax(F(f, k), F(f, (k + 1) % 3)));
  std::set<int> onCurves;
  for (const CageCurve& c : curves) {
    PIXELCLOTH_CHECK(c.vertices.size() >= 2, context << ": curve '" << c.name << "' has " << c.vertices.size()
                                                     << " vertices, expected at least 2");
    std::set<int> seen;
    for (size_t i = 0; i < c.vertices.size(); ++i) {
      int v = c.vertices[i];
      PIXELCLOTH_CHECK(v >= 0 && v < numVertices, context << ": curve '" << c.name << "' uses vertex " << v
                                                          << ", but the mesh has " << numVertices << " vertices");
      PIXELCLOTH_CHECK(seen.insert(v).second, context << ": curve '" << c.name << "' visits vertex " << v << " twice");
      onCurves.insert(v);
      bool hasNext = i + 1 < c.vertices.size() || c.closed;
      if (!hasNext) continue;
      int w = c.vertices[(i + 1) % c.vertices.size()];
      PIXELCLOTH_CHECK(meshEdges.count(std::minmax(v, w)),
                       context << ": curve '" << c.name << "' steps from vertex " << v << " to " << w
                               << ", which share no mesh edge; curves must follow mesh edges");
    }
  }
  for (const CageNode& n : nodes) {
    PIXELCLOTH_CHECK(onCurves.count(n.vertex),
                     context << ": node '" << n.name << "' (vertex " << n.vertex << ") lies on no curve");
  }
}

std::vector<CageNode> junctions(const std::vector<CageCurve>& curves) {
  std::map<int, std::vector<std::string>> through;
  for (const CageCurve& c : curves)
    for (int v : c.vertices) through[v].push_back(c.name);
  std::map<int, std::string> named;
  for (const CageCurve& c : curves) {
    if (!c.closed && !c.vertices.empty()) {
      named.emplace(c.vertices.front(), "");
      named.emplace(c.vertices.back(), "");
    }
  }
  for (const auto& [v, names] : through)
    if (names.size() >= 2) named.emplace(v, "");
  std::vector<CageNode> nodes;
  for (auto& [v, unused] : named) {
    std::vector<std::string> names = through[v];
    std::sort(names.begin(), names.end());
    std::string name;
    for (const std::string& n : names) name += (name.empty() ? "" : "/") + n;
    if (names.size() < 2) name += ":" + std::to_string(v);
    nodes.push_back({name, v});
  }
  return nodes;
}

nlohmann::json toJson(const Cage& cage) {
  nlohmann::json nodes = nlohmann::json::array(), curves = nlohmann::json::array();
  for (const CageNode& n : cage.nodes) nodes.push_back({{"name", n.name}, {"vertex", n.vertex}});
  for (const CageCurve& c : cage.curves)
    curves.push_back(
        {{"name", c.name}, {"kind", curveKindName(c.kind)}, {"closed", c.closed}, {"vertices", c.vertices}});
  return {{"nodes", nodes}, {"curves", curves}};
}

Cage cageFromJson(const nlohmann::json& json, const std::string& context) {
  Cage cage;
  const nlohmann::json& nodes = core::requireField(json, "nodes", context);
  const nlohmann::json& curves = core::requireField(json, "curves", context);
  PIXELCLOTH_CHECK(nodes.is_array() && curves.is_array(), context << ": 'nodes' and 'curves' must be arrays");
  for (const nlohmann::json& n : nodes)
    cage.nodes.push_back({core::requireValue<std::string>(n, "name", context + ": node"),
                          core::requireValue<int>(n, "vertex", context + ": node")});
  for (const nlohmann::json& c : curves) {
    CageCurve curve;
    curve.name = core::requireValue<std::string>(c, "name", context + ": curve");
    std::string where = context + ": curve '" + curve.name + "'";
    curve.kind = curveKindFromName(core::requireValue<std::string>(c, "kind", where), where);
    curve.closed = core::requireValue<bool>(c, "closed", where);
    curve.vertices = core::requireValue<std::vector<int>>(c, "vertices", where);
    cage.curves.push_back(std::move(curve));
  }
  return cage;
}

}  // namespace pixelcloth::cage
