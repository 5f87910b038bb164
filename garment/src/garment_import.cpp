// Garment import: an OBJ with per-corner UVs plus a JSON of layouts and cage polylines (garment.json's schema) become a
// Garment, validated so that everything downstream (cage, patches, pattern pictures) can rely on it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "garment_checks.h"
#include "garment_traits.h"
#include "pixelcloth/core/edge_key.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using core::edgeKey;

/// Two UVs of one vertex in one layout closer than this (metres of pattern space) are the same UV.
constexpr double kSameUvTolerance = 1e-9;
/// A UV triangle whose height is below this fraction of its longest edge, or below kMinUvHeight, is degenerate.
constexpr double kMinUvAspect = 1e-6;
constexpr double kMinUvHeight = 1e-7;

/// The kinds a cage line may have (the others are seams and openings, listed apart).
const std::vector<CurveKind> kCageLineKinds = {CurveKind::Loop, CurveKind::CentreLine, CurveKind::Split};

/// "vertex 12 (OBJ vertex 13)": the 0-based index the JSON uses and the 1-based number of the OBJ's `v` line.
std::string vertexName(int v) { return "vertex " + std::to_string(v) + " (OBJ vertex " + std::to_string(v + 1) + ")"; }

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// The faces around one undirected mesh edge (readMesh refuses more than two).
struct EdgeFaces {
  int faces[2] = {-1, -1};
  int count = 0;
  bool boundary() const { return count == 1; }
};

/// A seam, opening or cage line while it is checked: where it came from and its chain.
struct Polyline {
  std::string label;  // "seam 'side_left'", for messages
  std::string name;
  std::vector<int> vertices;
  bool closed = false;
};

/// Builds and checks a garment from a mesh and a JSON object in garment.json's schema. `objFile` and `jsonFile` name
/// where they came from in messages (the same name for a garment built in memory).
class Importer {
 public:
  Importer(core::Mesh mesh, json root, std::string objFile, std::string jsonFile)
      : root_(std::move(root)), objFile_(std::move(objFile)), jsonFile_(std::move(jsonFile)) {
    garment_.mesh = std::move(mesh);
  }

  Garment run() {
    checkMesh();
    readJsonHeader();
    garment_.traits = traitsOfGarmentJson(root_, garment_.mesh, jsonFile_);
    readLayouts();
    readPanels();
    buildVertexUV();
    buildEdges();
    readSeams();
    readOpenings();
    readCageLines();
    checkOpenings();
    checkLayoutCrossings();
    checkPatchesClosed();
    return std::move(garment_);
  }

 private:
  // ---------------------------------------------------------------------------------------------------------------
  // Files

  void checkMesh() {
    const core::Mesh& mesh = garment_.mesh;
    PIXELCLOTH_CHECK(mesh.hasUV(), objFile_ << ": no texture coordinates: the " << mesh.numFaces()
                                            << " faces carry no vt indices; expected every face as 'f v/vt ...' "
                                               "with UVs in pattern-space metres");
    std::vector<bool> used(mesh.numVertices(), false);
    for (int f = 0; f < mesh.numFaces(); ++f)
      for (int k = 0; k < 3; ++k) used[mesh.F(f, k)] = true;
    for (int v = 0; v < mesh.numVertices(); ++v) {
      PIXELCLOTH_CHECK(used[v], objFile_ << ": OBJ vertex " << v + 1 << " is used by no face; expected every vertex "
                                         << "on the garment surface");
    }
  }

  void readJsonHeader() {
    PIXELCLOTH_CHECK(root_.is_object(), jsonFile_ << ": expected a JSON object, found " << root_.type_name());
    if (root_.contains("format")) {
      const std::string format = core::requireValue<std::string>(root_, "format", jsonFile_);
      PIXELCLOTH_CHECK(format == "pixelcloth.garment",
                       jsonFile_ << ": field 'format' is '" << format << "', expected 'pixelcloth.garment'");
    }
    if (root_.contains("version")) {
      const int version = core::requireValue<int>(root_, "version", jsonFile_);
      PIXELCLOTH_CHECK(version == 1, jsonFile_ << ": field 'version' is " << version << ", expected 1");
    }
    garment_.name = core::requireValue<std::string>(root_, "name", jsonFile_);
    PIXELCLOTH_CHECK(!garment_.name.empty(), jsonFile_ << ": field 'name' is empty, expected the garment's name");
    if (root_.contains("mesh")) {
      const json& counts = root_["mesh"];
      const std::string where = jsonFile_ + ": mesh";
      for (const auto& [field, actual] : {std::pair<std::string, int>{"vertices", garment_.mesh.numVertices()},
                                          std::pair<std::string, int>{"faces", garment_.mesh.numFaces()}}) {
        if (!counts.is_object() || !counts.contains(field)) continue;
        const int declared = core::requireValue<int>(counts, field, where);
        PIXELCLOTH_CHECK(declared == actual, where << ": field '" << field << "' is " << declared << ", but "
                                                   << objFile_ << " has " << actual << " " << field
                                                   << "; the JSON describes another mesh");
      }
    }
  }

  // ---------------------------------------------------------------------------------------------------------------
  // Layouts and panels

  /// A list of unique, non-empty names: "layouts" entries are {"name": ...} objects or strings.
  std::vector<std::string> readNames(const json& list, const std::string& field) {
    std::vector<std::string> names;
    for (size_t i = 0; i < list.size(); ++i) {
      const json& item = list[i];
      const std::string where = jsonFile_ + ": " + field + "[" + std::to_string(i) + "]";
      std::string name;
      if (item.is_string()) {
        name = item.get<std::string>();
      } else {
        PIXELCLOTH_CHECK(item.is_object(),
                         where << " is " << item.type_name() << ", expected a name or an object with a 'name'");
        name = core::requireValue<std::string>(item, "name", where);
      }
      PIXELCLOTH_CHECK(!name.empty(), where << ": the name is empty");
      PIXELCLOTH_CHECK(std::find(names.begin(), names.end(), name) == names.end(),
                       jsonFile_ << ": " << field << ": the name '" << name << "' is used twice; names must be unique");
      names.push_back(name);
    }
    return names;
  }

  /// A per-face index field: #F integers in [0, count).
  Eigen::VectorXi readFaceIndices(const std::string& field, const std::vector<std::string>& names,
                                  const std::string& what) {
    const auto values = core::requireValue<std::vector<int>>(root_, field, jsonFile_);
    const int numFaces = garment_.mesh.numFaces();
    PIXELCLOTH_CHECK(static_cast<int>(values.size()) == numFaces,
                     jsonFile_ << ": field '" << field << "' has " << values.size()
                               << " entries, expected one per face of " << objFile_ << " (" << numFaces << ")");
    Eigen::VectorXi result(numFaces);
    for (int f = 0; f < numFaces; ++f) {
      PIXELCLOTH_CHECK(values[f] >= 0 && values[f] < static_cast<int>(names.size()),
                       jsonFile_ << ": field '" << field << "' gives face " << f + 1 << " " << what << " " << values[f]
                                 << ", expected 0.." << names.size() - 1 << " (an index into '" << what
                                 << "s': " << joined(names) << ")");
      result[f] = values[f];
    }
    return result;
  }

  void readLayouts() {
    const json& layouts = core::requireField(root_, "layouts", jsonFile_);
    PIXELCLOTH_CHECK(layouts.is_array() && !layouts.empty(),
                     jsonFile_ << ": field 'layouts' is "
                               << (layouts.is_array() ? "an empty array" : layouts.type_name())
                               << ", expected a non-empty array of layouts ({\"name\": ...} or names)");
    garment_.layouts = readNames(layouts, "layouts");
    const int numFaces = garment_.mesh.numFaces();
    if (root_.contains("face_layout")) {
      garment_.faceLayout = readFaceIndices("face_layout", garment_.layouts, "layout");
    } else {
      PIXELCLOTH_CHECK(garment_.numLayouts() == 1,
                       jsonFile_ << ": missing field 'face_layout'; with " << garment_.numLayouts() << " layouts ("
                                 << joined(garment_.layouts) << ") each face needs its layout index");
      garment_.faceLayout = Eigen::VectorXi::Zero(numFaces);
    }
    std::vector<int> facesPerLayout(garment_.numLayouts(), 0);
    for (int f = 0; f < numFaces; ++f) ++facesPerLayout[garment_.faceLayout[f]];
    for (int l = 0; l < garment_.numLayouts(); ++l) {
      PIXELCLOTH_CHECK(facesPerLayout[l] > 0, jsonFile_
                                                  << ": layout '" << garment_.layouts[l]
                                                  << "' has no faces in 'face_layout'; expected every layout used");
    }
  }

  void readPanels() {
    const int numFaces = garment_.mesh.numFaces();
    if (root_.contains("panels")) {
      const json& panels = root_["panels"];
      PIXELCLOTH_CHECK(panels.is_array() && !panels.empty(),
                       jsonFile_ << ": field 'panels' is "
                                 << (panels.is_array() ? "an empty array" : panels.type_name())
                                 << ", expected a non-empty array of panel names");
      garment_.panels = readNames(panels, "panels");
    } else {
      PIXELCLOTH_CHECK(!root_.contains("face_panel"),
                       jsonFile_ << ": field 'face_panel' needs the field 'panels' (the names its indices refer to)");
      garment_.panels = {garment_.name};
    }
    if (root_.contains("face_panel")) {
      garment_.facePanel = readFaceIndices("face_panel", garment_.panels, "panel");
    } else {
      PIXELCLOTH_CHECK(garment_.panels.size() == 1,
                       jsonFile_ << ": missing field 'face_panel'; with " << garment_.panels.size() << " panels ("
                                 << joined(garment_.panels) << ") each face needs its panel index");
      garment_.facePanel = Eigen::VectorXi::Zero(numFaces);
    }
  }

  // ---------------------------------------------------------------------------------------------------------------
  // UVs

  void buildVertexUV() {
    const core::Mesh& mesh = garment_.mesh;
    const int numLayouts = garment_.numLayouts();
    garment_.vertexUV = Eigen::MatrixXi::Constant(mesh.numVertices(), numLayouts, -1);
    Eigen::MatrixXi firstFace = Eigen::MatrixXi::Constant(mesh.numVertices(), numLayouts, -1);
    for (int f = 0; f < mesh.numFaces(); ++f) {
      const int l = garment_.faceLayout[f];
      const Eigen::Vector2d a = mesh.UV.row(mesh.FUV(f, 0)), b = mesh.UV.row(mesh.FUV(f, 1)),
                            c = mesh.UV.row(mesh.FUV(f, 2));
      const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
      const Eigen::Vector2d ab = b - a, ac = c - a;
      const double height = longest > 0 ? std::abs(ab.x() * ac.y() - ab.y() * ac.x()) / longest : 0.0;
      PIXELCLOTH_CHECK(
          height >= kMinUvAspect * longest && height >= kMinUvHeight,
          objFile_ << ": face " << f + 1 << " (layout '" << garment_.layouts[l]
                   << "') has a degenerate UV triangle: vt " << mesh.FUV(f, 0) + 1 << ", " << mesh.FUV(f, 1) + 1 << ", "
                   << mesh.FUV(f, 2) + 1 << " are " << (longest > 0 ? "collinear" : "the same point") << " (height "
                   << height << " m over a longest edge of " << longest << " m); expected a triangle of positive area");
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.F(f, k), t = mesh.FUV(f, k);
        int& known = garment_.vertexUV(v, l);
        if (known < 0) {
          known = t;
          firstFace(v, l) = f;
          continue;
        }
        if (known == t) continue;
        const Eigen::Vector2d first = mesh.UV.row(known), now = mesh.UV.row(t);
        PIXELCLOTH_CHECK((first - now).norm() <= kSameUvTolerance,
                         objFile_ << ": OBJ vertex " << v + 1 << " has two different UVs in layout '"
                                  << garment_.layouts[l] << "': vt " << known + 1 << " (" << first.x() << ", "
                                  << first.y() << ") in face " << firstFace(v, l) + 1 << " and vt " << t + 1 << " ("
                                  << now.x() << ", " << now.y() << ") in face " << f + 1
                                  << "; expected one UV per vertex and layout (faces with different UVs at a vertex "
                                     "belong to different layouts, see 'face_layout' in "
                                  << jsonFile_ << ")");
      }
    }
  }

  // ---------------------------------------------------------------------------------------------------------------
  // Edges and polylines

  void buildEdges() {
    const core::Mesh& mesh = garment_.mesh;
    edges_.reserve(static_cast<size_t>(mesh.numFaces()) * 2);
    for (int f = 0; f < mesh.numFaces(); ++f) {
      for (int k = 0; k < 3; ++k) {
        EdgeFaces& e = edges_[edgeKey(mesh.F(f, k), mesh.F(f, (k + 1) % 3))];
        if (e.count < 2) e.faces[e.count] = f;
        ++e.count;
      }
    }
  }

  const EdgeFaces* findEdge(int a, int b) const {
    auto it = edges_.find(edgeKey(a, b));
    return it == edges_.end() ? nullptr : &it->second;
  }

  /// The items of an optional list field: absent means none.
  const json& listField(const std::string& field) {
    static const json empty = json::array();
    if (!root_.contains(field)) return empty;
    const json& list = root_[field];
    PIXELCLOTH_CHECK(list.is_array(), jsonFile_ << ": field '" << field << "' is " << list.type_name()
                                                << ", expected an array of objects with 'name' and 'vertices'");
    return list;
  }

  /// Reads name and vertices of one list item and checks the chain: indices in range, no vertex twice, mesh edges
  /// between consecutive vertices (and last-first when closed).
  Polyline readPolyline(const json& item, const std::string& list, size_t index, const std::string& singular,
                        bool closed, std::set<std::string>& names) {
    const std::string at = jsonFile_ + ": " + list + "[" + std::to_string(index) + "]";
    PIXELCLOTH_CHECK(item.is_object(), at << " is " << item.type_name() << ", expected an object with 'name' and "
                                          << "'vertices'");
    Polyline line;
    line.name = core::requireValue<std::string>(item, "name", at);
    PIXELCLOTH_CHECK(!line.name.empty(), at << ": field 'name' is empty");
    line.label = singular + " '" + line.name + "'";
    PIXELCLOTH_CHECK(names.insert(line.name).second, jsonFile_ << ": " << list << ": the name '" << line.name
                                                               << "' is used twice; names must be unique");
    line.closed = closed;
    const std::string where = jsonFile_ + ": " + line.label;
    line.vertices = core::requireValue<std::vector<int>>(item, "vertices", where);
    const size_t minimum = closed ? 3 : 2;
    PIXELCLOTH_CHECK(line.vertices.size() >= minimum, where << ": 'vertices' has " << line.vertices.size()
                                                            << " entries, expected at least " << minimum
                                                            << (closed ? " (a closed loop)" : ""));
    const int numVertices = garment_.mesh.numVertices();
    std::map<int, size_t> seen;
    for (size_t i = 0; i < line.vertices.size(); ++i) {
      const int v = line.vertices[i];
      PIXELCLOTH_CHECK(v >= 0 && v < numVertices, where << ": 'vertices' entry " << i << " is " << v << ", but "
                                                        << objFile_ << " has " << numVertices
                                                        << " vertices; expected 0.." << numVertices - 1
                                                        << " (vertex indices in the JSON count from 0)");
      auto [it, inserted] = seen.emplace(v, i);
      PIXELCLOTH_CHECK(inserted, where << ": visits " << vertexName(v) << " twice ('vertices' entries " << it->second
                                       << " and " << i << "); expected each vertex once");
    }
    const size_t steps = closed ? line.vertices.size() : line.vertices.size() - 1;
    for (size_t i = 0; i < steps; ++i) {
      const int a = line.vertices[i], b = line.vertices[(i + 1) % line.vertices.size()];
      PIXELCLOTH_CHECK(findEdge(a, b) != nullptr,
                       where << ": steps from " << vertexName(a) << " to " << vertexName(b) << " ('vertices' entries "
                             << i << " and " << (i + 1) % line.vertices.size()
                             << (i + 1 == line.vertices.size() ? ", closing the loop" : "")
                             << "), which share no edge of " << objFile_ << "; expected a chain along mesh edges");
    }
    return line;
  }

  void readSeams() {
    const json& list = listField("seams");
    std::set<std::string> names;
    for (size_t i = 0; i < list.size(); ++i) {
      Polyline line = readPolyline(list[i], "seams", i, "seam", false, names);
      // The seam joins layouts where the faces on its two sides lie in different layouts.
      bool joins = false;
      for (size_t k = 0; k + 1 < line.vertices.size(); ++k) {
        const EdgeFaces& e = *findEdge(line.vertices[k], line.vertices[k + 1]);
        if (e.count == 2 && garment_.faceLayout[e.faces[0]] != garment_.faceLayout[e.faces[1]]) joins = true;
      }
      Seam seam{line.name, line.vertices, joins};
      if (list[i].contains("joins_layouts")) {
        const bool declared = core::requireValue<bool>(list[i], "joins_layouts", jsonFile_ + ": " + line.label);
        PIXELCLOTH_CHECK(declared == joins, jsonFile_ << ": " << line.label << ": field 'joins_layouts' is "
                                                      << std::boolalpha << declared
                                                      << ", but the faces on its two sides lie in "
                                                      << (joins ? "different layouts" : "the same layout")
                                                      << " (see 'face_layout'); expected " << joins << " or no field");
      }
      garment_.seams.push_back(seam);
      curves_.push_back(std::move(line));
    }
  }

  void readOpenings() {
    const json& list = listField("openings");
    std::set<std::string> names;
    for (size_t i = 0; i < list.size(); ++i) {
      Polyline line = readPolyline(list[i], "openings", i, "opening", true, names);
      garment_.openings.push_back(Opening{line.name, line.vertices});
      curves_.push_back(std::move(line));
    }
  }

  void readCageLines() {
    const json& list = listField("cage_lines");
    std::set<std::string> names;
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string at = jsonFile_ + ": cage_lines[" + std::to_string(i) + "]";
      bool closed = false;
      if (list[i].is_object() && list[i].contains("closed")) closed = core::requireValue<bool>(list[i], "closed", at);
      Polyline line = readPolyline(list[i], "cage_lines", i, "cage line", closed, names);
      const std::string kind = core::requireValue<std::string>(list[i], "kind", jsonFile_ + ": " + line.label);
      std::vector<std::string> kindNames;
      for (CurveKind k : kCageLineKinds) kindNames.push_back(curveKindName(k));
      const auto known = std::find(kindNames.begin(), kindNames.end(), kind);
      PIXELCLOTH_CHECK(known != kindNames.end(), jsonFile_ << ": " << line.label << ": field 'kind' is '" << kind
                                                           << "', expected one of: " << joined(kindNames));
      garment_.lines.push_back(CageLine{line.name, kCageLineKinds[known - kindNames.begin()], line.vertices, closed});
      curves_.push_back(std::move(line));
    }
  }

  // ---------------------------------------------------------------------------------------------------------------
  // Whole-garment checks

  /// Openings run along boundary edges with the cloth on their left; every boundary edge is in exactly one.
  void checkOpenings() {
    const core::Mesh& mesh = garment_.mesh;
    std::unordered_map<std::uint64_t, std::string> openingOf;
    for (const Opening& opening : garment_.openings) {
      const size_t n = opening.vertices.size();
      for (size_t i = 0; i < n; ++i) {
        const int a = opening.vertices[i], b = opening.vertices[(i + 1) % n];
        const EdgeFaces& e = *findEdge(a, b);
        PIXELCLOTH_CHECK(e.boundary(), jsonFile_ << ": opening '" << opening.name << "' runs from " << vertexName(a)
                                                 << " to " << vertexName(b) << ", an edge inside " << objFile_
                                                 << " (it has a face on both sides); openings follow the mesh "
                                                    "boundary");
        const int f = e.faces[0];
        int k = 0;
        while (mesh.F(f, k) != a) ++k;
        PIXELCLOTH_CHECK(mesh.F(f, (k + 1) % 3) == b,
                         jsonFile_ << ": opening '" << opening.name << "' runs against the boundary from "
                                   << vertexName(a) << " to " << vertexName(b) << " (face " << f + 1 << " of "
                                   << objFile_ << " runs the other way); expected the cloth on the opening's left: "
                                   << "reverse its 'vertices'");
        auto [it, inserted] = openingOf.emplace(edgeKey(a, b), opening.name);
        PIXELCLOTH_CHECK(inserted, jsonFile_ << ": the boundary edge from " << vertexName(a) << " to " << vertexName(b)
                                             << " is in opening '" << it->second << "' and in opening '" << opening.name
                                             << "'; expected each boundary edge in one opening");
      }
    }
    int missing = 0;
    std::uint64_t firstMissing = 0;
    for (const auto& [key, e] : edges_) {
      if (!e.boundary() || openingOf.count(key)) continue;
      if (missing == 0 || key < firstMissing) firstMissing = key;
      ++missing;
    }
    const int a = static_cast<int>(firstMissing >> 32), b = static_cast<int>(firstMissing & 0xffffffffu);
    PIXELCLOTH_CHECK(missing == 0, jsonFile_ << ": " << missing << " boundary edges of " << objFile_
                                             << " belong to no opening, the first from " << vertexName(a) << " to "
                                             << vertexName(b) << "; expected every mesh boundary listed under "
                                             << "'openings' (" << garment_.openings.size() << " given)");
  }

  /// An edge whose two faces lie in different layouts is a UV discontinuity: it must be sewn, i.e. on a seam.
  void checkLayoutCrossings() {
    std::set<std::uint64_t> seamEdges;
    for (const Seam& seam : garment_.seams)
      for (size_t i = 0; i + 1 < seam.vertices.size(); ++i)
        seamEdges.insert(edgeKey(seam.vertices[i], seam.vertices[i + 1]));
    const core::Mesh& mesh = garment_.mesh;
    for (int f = 0; f < mesh.numFaces(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
        const EdgeFaces& e = *findEdge(a, b);
        if (e.count != 2 || e.faces[0] != f) continue;  // each interior edge once
        const int la = garment_.faceLayout[e.faces[0]], lb = garment_.faceLayout[e.faces[1]];
        PIXELCLOTH_CHECK(la == lb || seamEdges.count(edgeKey(a, b)),
                         jsonFile_ << ": the edge from " << vertexName(a) << " to " << vertexName(b) << " joins faces "
                                   << e.faces[0] + 1 << " (layout '" << garment_.layouts[la] << "') and "
                                   << e.faces[1] + 1 << " (layout '" << garment_.layouts[lb]
                                   << "') but lies on no seam; expected layouts to meet only along seams");
      }
    }
  }

  /// Flood-fills the faces across edges on no curve into patches: each open curve must end on another curve or the
  /// mesh boundary, and every curve edge inside the mesh must have different patches on its two sides.
  void checkPatchesClosed() {
    const core::Mesh& mesh = garment_.mesh;
    std::set<std::uint64_t> curveEdges;
    std::vector<std::vector<int>> curvesAt(mesh.numVertices());
    for (size_t c = 0; c < curves_.size(); ++c) {
      const Polyline& line = curves_[c];
      const size_t n = line.vertices.size();
      for (size_t i = 0; i < n; ++i) curvesAt[line.vertices[i]].push_back(static_cast<int>(c));
      for (size_t i = 0; i < (line.closed ? n : n - 1); ++i)
        curveEdges.insert(edgeKey(line.vertices[i], line.vertices[(i + 1) % n]));
    }
    std::vector<bool> onBoundary(mesh.numVertices(), false);
    for (const auto& [key, e] : edges_) {
      if (!e.boundary()) continue;
      onBoundary[key >> 32] = true;
      onBoundary[key & 0xffffffffu] = true;
    }

    for (size_t c = 0; c < curves_.size(); ++c) {
      const Polyline& line = curves_[c];
      if (line.closed) continue;
      for (int end : {line.vertices.front(), line.vertices.back()}) {
        const bool onOther = std::any_of(curvesAt[end].begin(), curvesAt[end].end(),
                                         [&](int other) { return other != static_cast<int>(c); });
        PIXELCLOTH_CHECK(onOther || onBoundary[end],
                         jsonFile_ << ": " << line.label << " ends at " << vertexName(end)
                                   << ", which lies on no other seam, opening or cage line nor on the mesh boundary: "
                                   << "the curve stops inside a patch and does not close it; expected each end of an "
                                   << "open curve on another curve or the boundary");
      }
    }

    // Union-find over faces, joined across edges that are on no curve.
    std::vector<int> parent(mesh.numFaces());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int f) {
      while (parent[f] != f) f = parent[f] = parent[parent[f]];
      return f;
    };
    for (const auto& [key, e] : edges_) {
      if (e.count == 2 && !curveEdges.count(key)) parent[find(e.faces[0])] = find(e.faces[1]);
    }
    for (const Polyline& line : curves_) {
      const size_t n = line.vertices.size();
      for (size_t i = 0; i < (line.closed ? n : n - 1); ++i) {
        const int a = line.vertices[i], b = line.vertices[(i + 1) % n];
        const EdgeFaces& e = *findEdge(a, b);
        PIXELCLOTH_CHECK(e.count != 2 || find(e.faces[0]) != find(e.faces[1]),
                         jsonFile_ << ": " << line.label << " does not close a patch: faces " << e.faces[0] + 1
                                   << " and " << e.faces[1] + 1 << " on the two sides of its edge from "
                                   << vertexName(a) << " to " << vertexName(b)
                                   << " are joined around it without crossing a seam, opening or cage line; expected "
                                   << "every curve to separate two patches");
      }
    }
  }

  json root_;
  std::string objFile_, jsonFile_;
  Garment garment_;
  std::unordered_map<std::uint64_t, EdgeFaces> edges_;
  std::vector<Polyline> curves_;  // seams, then openings, then cage lines
};

}  // namespace

Garment importGarment(const fs::path& obj, const fs::path& cageJson) {
  const std::string objFile = obj.string();
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::exists(obj, ec), objFile << ": no such file; expected an OBJ mesh with per-corner texture "
                                                   "coordinates (vt) in pattern space");
  PIXELCLOTH_CHECK(fs::is_regular_file(obj, ec), objFile << ": not a regular file; expected an OBJ mesh");
  core::Mesh mesh = core::readMesh(obj);
  return Importer(std::move(mesh), core::readJson(cageJson), objFile, cageJson.string()).run();
}

void validateGarment(const Garment& garment, const std::string& context) {
  const json root = garmentJson(garment);
  const Garment checked = Importer(garment.mesh, root, context, context).run();
  PIXELCLOTH_ASSERT(checked.vertexUV == garment.vertexUV,
                    context << ": the garment's vertexUV differs from what its faces' UVs and layouts give");
}

}  // namespace pixelcloth::garment
