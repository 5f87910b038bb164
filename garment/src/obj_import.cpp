// Garment OBJ import without a cage file: UV islands become layouts, OBJ groups (or the islands) panels, the edges
// between panels seams, the boundary loops openings, each named by where it sits; and the exporter that writes our
// garments the way users' cloth programs do (docs/garment-import.md).
#include "pixelcloth/garment/obj_import.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <random>
#include <set>
#include <sstream>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "garment_checks.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/edge_key.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh_io.h"

namespace pixelcloth::garment {

namespace fs = std::filesystem;

namespace {

using core::edgeKey;

/// Two corners whose UVs are closer than this (UV units) are the same UV.
constexpr double kSameUv = 1e-9;
/// An island is in metres of cloth when its median edge is this many times as long in 3D as in UV.
constexpr double kMinEdgeRatio = 0.9, kMaxEdgeRatio = 1.1;
/// A seam is split where the pattern outline turns by more than this, measured over kCornerWindow of outline.
constexpr double kCornerDegrees = 45;
constexpr double kCornerWindow = 0.015;
/// A garment's height must lie in this range, metres.
constexpr double kMinHeight = 0.05, kMaxHeight = 3.0;
/// A garment is lying along z when its z extent is this many times its y extent.
constexpr double kLyingRatio = 1.5;
/// A cut endpoint moves to a vertex where the neighbouring piece changes within this fraction of its boundary stretch.
constexpr double kCutSnapFraction = 0.15;
constexpr int kMaxCuts = 64;

std::string number(double value, int digits = 3) {
  std::ostringstream out;
  out << std::setprecision(digits) << value;
  return out.str();
}

Eigen::Vector3d turnToYUp(const Eigen::Vector3d& p, char up) {
  return up == 'z' ? Eigen::Vector3d(p.x(), p.z(), -p.y()) : p;
}

Eigen::Vector3d turnFromYUp(const Eigen::Vector3d& p, char up) {
  return up == 'z' ? Eigen::Vector3d(p.x(), -p.z(), p.y()) : p;
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Union-find over 0..n-1.
struct Components {
  std::vector<int> parent;
  explicit Components(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
  /// Dense labels 0.. in order of each component's first member.
  std::vector<int> labels(int& count) {
    std::vector<int> label(parent.size(), -1), ofRoot(parent.size(), -1);
    count = 0;
    for (size_t i = 0; i < parent.size(); ++i) {
      int& l = ofRoot[find(static_cast<int>(i))];
      if (l < 0) l = count++;
      label[i] = l;
    }
    return label;
  }
};

// ---------------------------------------------------------------------------------------------------------------------
// OBJ groups: core::readMesh keeps no `g` / `o` / `usemtl` lines, so they are read here and mapped to the triangles in
// the order readMesh builds them (each polygon of n corners gives n - 2 triangles, in file order).

struct FaceGroups {
  std::string keyword;             ///< "g", "o" or "usemtl": the first with two or more names on faces; "" for none
  std::vector<std::string> names;  ///< group names in order of first use
  std::vector<int> faceGroup;      ///< #F, index into names; empty when keyword is ""
};

FaceGroups scanGroups(const fs::path& path, int numFaces) {
  const std::string text = core::readTextFile(path);
  const std::string file = path.string();
  const std::array<std::string, 3> keywords = {"g", "o", "usemtl"};
  std::array<std::vector<std::string>, 3> names;
  std::array<int, 3> current = {-1, -1, -1};
  std::vector<std::array<int, 3>> faces;
  faces.reserve(numFaces);
  size_t pos = 0;
  for (int line = 1; pos < text.size(); ++line) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::istringstream in(text.substr(pos, end - pos));
    pos = end + 1;
    std::string keyword;
    if (!(in >> keyword) || keyword[0] == '#') continue;
    if (keyword == "f") {
      int corners = 0;
      for (std::string token; in >> token;) ++corners;
      PIXELCLOTH_ASSERT(corners >= 3,
                        file << " line " << line << ": readMesh accepted a face of " << corners << " corners");
      for (int k = 0; k + 2 < corners; ++k) faces.push_back(current);
      continue;
    }
    for (size_t w = 0; w < keywords.size(); ++w) {
      if (keyword != keywords[w]) continue;
      std::string rest, word;
      while (in >> word) rest += (rest.empty() ? "" : " ") + word;
      if (rest.empty()) {
        PIXELCLOTH_CHECK(keyword != "usemtl",
                         file << ": 'usemtl' without a material name (line " << line << "); expected 'usemtl NAME'");
        rest = "default";  // a bare `g` or `o` returns to the default group
      }
      auto it = std::find(names[w].begin(), names[w].end(), rest);
      current[w] = static_cast<int>(it - names[w].begin());
      if (it == names[w].end()) names[w].push_back(rest);
    }
  }
  PIXELCLOTH_ASSERT(static_cast<int>(faces.size()) == numFaces,
                    file << ": " << faces.size() << " triangles from the 'f' lines, readMesh built " << numFaces);
  FaceGroups groups;
  for (size_t w = 0; w < keywords.size(); ++w) {
    std::vector<int> used;
    for (const auto& face : faces)
      if (std::find(used.begin(), used.end(), face[w]) == used.end()) used.push_back(face[w]);
    if (used.size() < 2) continue;
    groups.keyword = keywords[w];
    std::map<int, int> index;
    for (int id : used) {
      index[id] = static_cast<int>(groups.names.size());
      groups.names.push_back(id < 0 ? "(no " + keywords[w] + ")" : names[w][id]);
    }
    groups.faceGroup.resize(numFaces);
    for (int f = 0; f < numFaces; ++f) groups.faceGroup[f] = index[faces[f][w]];
    break;
  }
  return groups;
}

/// A group name as a panel name: lower case, runs of anything but letters and digits as one '_'.
std::string sanitized(const std::string& name) {
  std::string out;
  for (unsigned char c : name) {
    if (std::isalnum(c)) {
      out += static_cast<char>(std::tolower(c));
    } else if (!out.empty() && out.back() != '_') {
      out += '_';
    }
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out;
}

/// The mesh edges: the faces on each side and whether the UVs continue across.
struct Edge {
  int a = -1, b = -1;
  int faces[2] = {-1, -1};
  int count = 0;
  bool joined = false;  ///< two faces whose corners at a and at b have the same UVs
};

/// A boundary loop of the mesh and where it sits.
struct Loop {
  std::vector<int> vertices;                           ///< cloth on the left
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< length-weighted
  Eigen::AlignedBox3d box;
  std::string name;
};

/// A seam chain while it is named.
struct Chain {
  std::vector<int> vertices;
  int panels[2] = {-1, -1};
  int layouts[2] = {-1, -1};
  double length = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::string name;
};

enum class Role { Torso, Sleeve, Other };

class ObjImporter {
 public:
  ObjImporter(const fs::path& path, const ObjImportOptions& options) : path_(path), options_(options) {
    file_ = path.string();
  }

  Garment run(ObjImportReport* report) {
    options_.validate();
    read();
    place();
    orientFaces();
    buildEdges();
    findLoops();
    checkWelded();
    checkPlacement();
    findIslands();
    for (int i = 0; i < numIslands_; ++i) fixIslandUVs(i);
    cutIslands();
    findPanels();
    buildUVs();
    findSeams();
    nameOpenings();
    namePanels();
    nameSeams();
    Garment garment = assemble();
    validateGarment(garment, file_);
    if (report) {
      for (const auto& [island, text] : islandNotes_) report->notes.push_back(islandLabel(island) + ": " + text);
      report->notes.insert(report->notes.end(), notes_.begin(), notes_.end());
    }
    return garment;
  }

 private:
  // -------------------------------------------------------------------------------------------------------------------
  // Reading and placement

  void read() {
    std::error_code ec;
    PIXELCLOTH_CHECK(fs::exists(path_, ec), file_ << ": no such file; expected a garment OBJ with per-corner texture "
                                                     "coordinates (vt)");
    PIXELCLOTH_CHECK(fs::is_regular_file(path_, ec), file_ << ": not a regular file; expected a garment OBJ");
    mesh_ = core::readMesh(path_);
    PIXELCLOTH_CHECK(mesh_.hasUV(), file_ << ": no texture coordinates: the " << mesh_.numFaces()
                                          << " faces carry no vt indices; expected every face as 'f v/vt ...' with "
                                             "the garment's sewing pattern as UVs");
    numVertices_ = mesh_.numVertices();
    numFaces_ = mesh_.numFaces();
    std::vector<bool> used(numVertices_, false);
    for (int f = 0; f < numFaces_; ++f)
      for (int k = 0; k < 3; ++k) used[mesh_.F(f, k)] = true;
    for (int v = 0; v < numVertices_; ++v) {
      PIXELCLOTH_CHECK(used[v], file_ << ": vertex " << v + 1 << " is used by no face; expected every vertex on the "
                                      << "garment surface");
    }
    groups_ = scanGroups(path_, numFaces_);
    cornerUV_.resize(3 * numFaces_, 2);
    for (int f = 0; f < numFaces_; ++f)
      for (int k = 0; k < 3; ++k) cornerUV_.row(3 * f + k) = mesh_.UV.row(mesh_.FUV(f, k));
    name_ = options_.name.empty() ? path_.stem().string() : options_.name;
    PIXELCLOTH_CHECK(!name_.empty(), file_ << ": the file has no stem to name the garment after; give a name");
  }

  void place() {
    for (int v = 0; v < numVertices_; ++v) {
      const Eigen::Vector3d p = mesh_.V.row(v).transpose();
      mesh_.V.row(v) = (turnToYUp(p, options_.up) * options_.scale + options_.translate).transpose();
    }
  }

  Eigen::Vector3d faceNormalTimesTwiceArea(int f) const {
    const Eigen::Vector3d a = mesh_.V.row(mesh_.F(f, 0)), b = mesh_.V.row(mesh_.F(f, 1)),
                          c = mesh_.V.row(mesh_.F(f, 2));
    return (b - a).cross(c - a);
  }

  Eigen::Vector3d faceCentroid(int f) const {
    return (mesh_.V.row(mesh_.F(f, 0)) + mesh_.V.row(mesh_.F(f, 1)) + mesh_.V.row(mesh_.F(f, 2))).transpose() / 3.0;
  }

  /// Faces are turned round when, seen from the garment's centre, they clearly face inwards.
  void orientFaces() {
    double area = 0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int f = 0; f < numFaces_; ++f) {
      const double a = 0.5 * faceNormalTimesTwiceArea(f).norm();
      area += a;
      centre += a * faceCentroid(f);
    }
    PIXELCLOTH_CHECK(area > 0, file_ << ": every face has zero area in 3D; expected a garment surface");
    centre /= area;
    centroid_ = centre;
    double outwards = 0, spread = 0;
    for (int f = 0; f < numFaces_; ++f) {
      const Eigen::Vector3d n = 0.5 * faceNormalTimesTwiceArea(f);
      const Eigen::Vector3d d = faceCentroid(f) - centre;
      outwards += n.dot(d);
      spread += n.norm() * d.norm();
    }
    if (spread > 0 && outwards < -0.05 * spread) {
      mesh_.F.col(1).swap(mesh_.F.col(2));
      mesh_.FUV.col(1).swap(mesh_.FUV.col(2));
      for (int f = 0; f < numFaces_; ++f) {
        const Eigen::RowVector2d t = cornerUV_.row(3 * f + 1);
        cornerUV_.row(3 * f + 1) = cornerUV_.row(3 * f + 2);
        cornerUV_.row(3 * f + 2) = t;
      }
      notes_.push_back("the faces pointed into the garment: turned round");
    }
  }

  int cornerOf(int f, int v) const {
    for (int k = 0; k < 3; ++k)
      if (mesh_.F(f, k) == v) return k;
    PIXELCLOTH_ASSERT(false, "face " << f << " has no vertex " << v);
    return 0;
  }

  bool sameUV(int f, int v, int g) const {
    const int kf = cornerOf(f, v), kg = cornerOf(g, v);
    if (mesh_.FUV(f, kf) == mesh_.FUV(g, kg)) return true;
    return (cornerUV_.row(3 * f + kf) - cornerUV_.row(3 * g + kg)).norm() <= kSameUv;
  }

  void buildEdges() {
    std::unordered_map<std::uint64_t, int> index;
    index.reserve(3 * numFaces_);
    faceEdge_.resize(3 * numFaces_);
    vertexFaces_.assign(numVertices_, {});
    for (int f = 0; f < numFaces_; ++f) {
      for (int k = 0; k < 3; ++k) {
        const int a = mesh_.F(f, k), b = mesh_.F(f, (k + 1) % 3);
        vertexFaces_[a].push_back(f);
        auto [it, inserted] = index.emplace(edgeKey(a, b), static_cast<int>(edges_.size()));
        if (inserted) {
          Edge e;
          e.a = std::min(a, b);
          e.b = std::max(a, b);
          edges_.push_back(e);
        }
        Edge& e = edges_[it->second];
        PIXELCLOTH_ASSERT(e.count < 2, "readMesh accepted an edge with three faces");
        e.faces[e.count++] = f;
        faceEdge_[3 * f + k] = it->second;
      }
    }
    edgeIndex_ = std::move(index);
    for (Edge& e : edges_)
      e.joined = e.count == 2 && sameUV(e.faces[0], e.a, e.faces[1]) && sameUV(e.faces[0], e.b, e.faces[1]);
  }

  /// Boundary loops, each along its faces' orientation (cloth on the left).
  void findLoops() {
    std::vector<int> next(numVertices_, -1);
    onBoundary_.assign(numVertices_, false);
    for (int f = 0; f < numFaces_; ++f) {
      for (int k = 0; k < 3; ++k) {
        if (edges_[faceEdge_[3 * f + k]].count != 1) continue;
        const int a = mesh_.F(f, k), b = mesh_.F(f, (k + 1) % 3);
        PIXELCLOTH_CHECK(next[a] < 0, file_ << ": vertex " << a + 1 << " lies on two stretches of the garment's "
                                            << "boundary (two openings, or two parts of one, touch there); expected "
                                            << "openings that meet at no vertex");
        next[a] = b;
        onBoundary_[a] = onBoundary_[b] = true;
      }
    }
    std::vector<bool> seen(numVertices_, false);
    for (int start = 0; start < numVertices_; ++start) {
      if (next[start] < 0 || seen[start]) continue;
      Loop loop;
      double length = 0;
      for (int v = start; !seen[v]; v = next[v]) {
        PIXELCLOTH_ASSERT(next[v] >= 0, "the boundary stops at vertex " << v);
        seen[v] = true;
        loop.vertices.push_back(v);
        const Eigen::Vector3d p = mesh_.V.row(v), q = mesh_.V.row(next[v]);
        length += (q - p).norm();
        loop.centroid += (q - p).norm() * 0.5 * (p + q);
        loop.box.extend(p);
      }
      loop.centroid = length > 0 ? Eigen::Vector3d(loop.centroid / length) : loop.box.center();
      loops_.push_back(std::move(loop));
    }
  }

  /// Refuses pattern pieces that are not sewn: two boundary edges at the same place (an unwelded seam, each piece with
  /// its own copy of the seam's vertices).
  void checkWelded() {
    Eigen::AlignedBox3d box;
    for (int v = 0; v < numVertices_; ++v) box.extend(Eigen::Vector3d(mesh_.V.row(v).transpose()));
    const double tolerance = 1e-6 * std::max(box.diagonal().norm(), 1e-12);
    auto cellOf = [&](int v) {
      const Eigen::Vector3d p = (mesh_.V.row(v).transpose() - box.min()) / (4 * tolerance);
      return std::array<long long, 3>{static_cast<long long>(p.x()), static_cast<long long>(p.y()),
                                      static_cast<long long>(p.z())};
    };
    std::map<std::array<long long, 3>, std::vector<int>> grid;
    for (int v = 0; v < numVertices_; ++v)
      if (onBoundary_[v]) grid[cellOf(v)].push_back(v);
    auto twinOf = [&](int v, int other) {  // a boundary vertex at v's place other than v, preferring `other`'s twin
      std::vector<int> twins;
      const std::array<long long, 3> cell = cellOf(v);
      for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy)
          for (long long dz = -1; dz <= 1; ++dz) {
            auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
            if (it == grid.end()) continue;
            for (int w : it->second)
              if (w != v && w != other && (mesh_.V.row(w) - mesh_.V.row(v)).norm() <= tolerance) twins.push_back(w);
          }
      return twins;
    };
    for (const Edge& e : edges_) {
      if (e.count != 1) continue;
      for (int a : twinOf(e.a, e.b)) {
        for (int b : twinOf(e.b, e.a)) {
          auto it = edgeIndex_.find(edgeKey(a, b));
          if (it == edgeIndex_.end() || edges_[it->second].count != 1) continue;
          PIXELCLOTH_FAIL(
              file_ << ": the boundary edges from vertex " << e.a + 1 << " to " << e.b + 1 << " and from vertex "
                    << a + 1 << " to " << b + 1
                    << " lie at the same place: the pattern pieces are not sewn (each has its own copy "
                    << "of the seam's vertices); expected seams welded, one vertex per seam point with a UV "
                    << "on each side (export with welded seams)");
        }
      }
    }
  }

  /// Refuses a garment lying along z or of a size that is not metres, naming the option that fixes it.
  void checkPlacement() {
    Eigen::AlignedBox3d box;
    for (int v = 0; v < numVertices_; ++v) box.extend(Eigen::Vector3d(mesh_.V.row(v).transpose()));
    box_ = box;
    const Eigen::Vector3d size = box.sizes();
    double spreadY = 0, spreadZ = 0;
    for (const Loop& a : loops_) {
      for (const Loop& b : loops_) {
        spreadY = std::max(spreadY, std::abs(a.centroid.y() - b.centroid.y()));
        spreadZ = std::max(spreadZ, std::abs(a.centroid.z() - b.centroid.z()));
      }
    }
    const bool lyingBySize = size.z() > kLyingRatio * size.y();
    const bool lyingByOpenings = spreadZ > 2 * spreadY && spreadZ > 0.1 * size.maxCoeff();
    const char other = options_.up == 'y' ? 'z' : 'y';
    PIXELCLOTH_CHECK(!lyingBySize && !lyingByOpenings,
                     file_ << ": the garment lies along z, not standing along y (extents x " << number(size.x())
                           << ", y " << number(size.y()) << ", z " << number(size.z()) << " m; its openings are "
                           << number(spreadZ) << " m apart along z and " << number(spreadY)
                           << " m along y), read with --up " << options_.up
                           << "; expected Y up (neckline or waist above the hem along y): is the file "
                           << static_cast<char>(std::toupper(other)) << "-up? use --up " << other);
    const double height = size.y();
    if (height >= kMinHeight && height <= kMaxHeight) return;
    std::string advice;
    const std::pair<double, const char*> units[] = {
        {0.01, "centimetres"}, {0.001, "millimetres"}, {0.0254, "inches"}, {0.1, "decimetres"}};
    for (const auto& [metres, unit] : units) {
      if (height * metres >= 0.2 && height * metres <= 2.0) {
        advice = std::string(": is it in ") + unit + "? use --scale " + number(options_.scale * metres, 6);
        break;
      }
    }
    if (advice.empty()) {
      const double factor = 0.7 / std::max(height, 1e-12);
      advice = "; use --scale S to give its size in metres (--scale " + number(options_.scale * factor, 3) +
               " makes it 0.7 m tall)";
    }
    PIXELCLOTH_FAIL(file_ << ": the garment is " << number(height) << " m tall (y from " << number(box.min().y())
                          << " to " << number(box.max().y()) << " after --scale " << number(options_.scale, 6)
                          << "); expected " << kMinHeight << " to " << kMaxHeight << " m" << advice);
  }

  // -------------------------------------------------------------------------------------------------------------------
  // UV islands

  void findIslands() {
    Components components(numFaces_);
    for (const Edge& e : edges_)
      if (e.joined) components.join(e.faces[0], e.faces[1]);
    island_ = components.labels(numIslands_);
    islandFaces_.assign(numIslands_, {});
    for (int f = 0; f < numFaces_; ++f) islandFaces_[island_[f]].push_back(f);
  }

  /// "island 3 (faces from 1201, group 'Sleeve')": for messages before the islands have names.
  std::string islandWhere(int island) const {
    std::string where = "island " + std::to_string(island + 1) + " (" + std::to_string(islandFaces_[island].size()) +
                        " faces from face " + std::to_string(islandFaces_[island].front() + 1);
    if (!groups_.keyword.empty())
      where += ", " + groups_.keyword + " '" + groups_.names[groups_.faceGroup[islandFaces_[island].front()]] + "'";
    return where + ")";
  }

  double uvSignedArea(int f) const {
    const Eigen::Vector2d a = cornerUV_.row(3 * f), b = cornerUV_.row(3 * f + 1), c = cornerUV_.row(3 * f + 2);
    return 0.5 * cross2(b - a, c - a);
  }

  /// Orientation, overlap and scale of one island's UVs: mirrored when clockwise, refused when folded or overlapping,
  /// rescaled to its 3D area when not in metres of cloth.
  void fixIslandUVs(int island) {
    const std::vector<int>& faces = islandFaces_[island];
    Eigen::AlignedBox2d box;
    for (int f : faces)
      for (int k = 0; k < 3; ++k) box.extend(Eigen::Vector2d(cornerUV_.row(3 * f + k).transpose()));
    const double extent = box.sizes().maxCoeff();
    const double tolerance = 1e-12 * extent * extent;
    int clockwise = 0, counter = 0, firstClockwise = -1, firstCounter = -1;
    for (int f : faces) {
      const double area = uvSignedArea(f);
      if (area < -tolerance) {
        if (clockwise++ == 0) firstClockwise = f;
      } else if (area > tolerance) {
        if (counter++ == 0) firstCounter = f;
      }
    }
    PIXELCLOTH_CHECK(clockwise == 0 || counter == 0,
                     file_ << ": " << islandWhere(island) << " is folded in UV: face " << firstClockwise + 1
                           << " runs clockwise and face " << firstCounter + 1 << " counter-clockwise (" << clockwise
                           << " of " << faces.size() << " faces clockwise); expected a flat pattern piece, every "
                           << "triangle of a UV island the same way round");
    if (clockwise > 0) {
      for (int f : faces)
        for (int k = 0; k < 3; ++k) cornerUV_(3 * f + k, 0) = -cornerUV_(3 * f + k, 0);
      islandNotes_.emplace_back(island, "UVs mirrored (they ran clockwise seen from outside)");
    }
    checkOverlap(island);

    std::vector<double> ratios;
    double area3 = 0, areaUV = 0;
    for (int f : faces) {
      area3 += 0.5 * faceNormalTimesTwiceArea(f).norm();
      areaUV += std::abs(uvSignedArea(f));
      for (int k = 0; k < 3; ++k) {
        const double lengthUV = (cornerUV_.row(3 * f + (k + 1) % 3) - cornerUV_.row(3 * f + k)).norm();
        const double length3 = (mesh_.V.row(mesh_.F(f, (k + 1) % 3)) - mesh_.V.row(mesh_.F(f, k))).norm();
        if (lengthUV > 0) ratios.push_back(length3 / lengthUV);
      }
    }
    if (ratios.empty() || areaUV <= 0) return;  // degenerate: refused by the checks, naming the face
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    const double median = ratios[ratios.size() / 2];
    if (median >= kMinEdgeRatio && median <= kMaxEdgeRatio) return;
    const double factor = std::sqrt(area3 / areaUV);
    for (int f : faces)
      for (int k = 0; k < 3; ++k) cornerUV_.row(3 * f + k) *= factor;
    islandNotes_.emplace_back(island, "UVs rescaled x" + number(factor) + " to its 3D area (its edges were " +
                                          number(median) + " times as long in 3D as in UV; expected metres of cloth)");
  }

  /// Refuses an island whose UV outline crosses itself (its UVs overlap).
  void checkOverlap(int island) {
    struct Segment {
      Eigen::Vector2d p, q;
      int face;
    };
    std::vector<Segment> segments;
    for (int f : islandFaces_[island]) {
      for (int k = 0; k < 3; ++k) {
        const Edge& e = edges_[faceEdge_[3 * f + k]];
        if (e.joined) continue;
        segments.push_back({cornerUV_.row(3 * f + k).transpose(), cornerUV_.row(3 * f + (k + 1) % 3).transpose(), f});
      }
    }
    if (segments.size() < 4) return;
    Eigen::AlignedBox2d box;
    double total = 0;
    for (const Segment& s : segments) box.extend(s.p), box.extend(s.q), total += (s.q - s.p).norm();
    const double cell = std::max(2 * total / segments.size(), 1e-12);
    const int nx = std::min(4096, static_cast<int>(box.sizes().x() / cell) + 1);
    const int ny = std::min(4096, static_cast<int>(box.sizes().y() / cell) + 1);
    std::unordered_map<std::int64_t, std::vector<int>> grid;
    auto cellOf = [&](const Eigen::Vector2d& p, int& i, int& j) {
      i = std::clamp(static_cast<int>((p.x() - box.min().x()) / cell), 0, nx - 1);
      j = std::clamp(static_cast<int>((p.y() - box.min().y()) / cell), 0, ny - 1);
    };
    for (size_t s = 0; s < segments.size(); ++s) {
      int i0, j0, i1, j1;
      cellOf(segments[s].p.cwiseMin(segments[s].q), i0, j0);
      cellOf(segments[s].p.cwiseMax(segments[s].q), i1, j1);
      for (int i = i0; i <= i1; ++i)
        for (int j = j0; j <= j1; ++j) grid[static_cast<std::int64_t>(i) * ny + j].push_back(static_cast<int>(s));
    }
    auto orientation = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
      const double value = cross2(b - a, c - a);
      const double scale = (b - a).norm() * (c - a).norm();
      return value > 1e-12 * scale ? 1 : value < -1e-12 * scale ? -1 : 0;
    };
    for (const auto& [key, members] : grid) {
      for (size_t x = 0; x < members.size(); ++x) {
        for (size_t y = x + 1; y < members.size(); ++y) {
          const Segment &s = segments[members[x]], &t = segments[members[y]];
          auto near = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return (a - b).norm() <= kSameUv; };
          if (near(s.p, t.p) || near(s.p, t.q) || near(s.q, t.p) || near(s.q, t.q)) continue;
          const int o1 = orientation(s.p, s.q, t.p), o2 = orientation(s.p, s.q, t.q);
          const int o3 = orientation(t.p, t.q, s.p), o4 = orientation(t.p, t.q, s.q);
          const bool cross = o1 * o2 < 0 && o3 * o4 < 0;
          PIXELCLOTH_CHECK(!cross, file_ << ": " << islandWhere(island) << " overlaps itself in UV: its outline "
                                         << "crosses itself at faces " << s.face + 1 << " and " << t.face + 1
                                         << "; expected a flat pattern piece whose UVs do not overlap");
        }
      }
    }
  }

  // -------------------------------------------------------------------------------------------------------------------
  // Cutting islands that hold a vertex twice

  /// Pieces: faces joined across UV-continuous edges that are not cut. Classes: the corners of one vertex joined the
  /// same way (one class per vertex and piece when the piece holds no vertex twice).
  void findPieces() {
    Components faces(numFaces_), corners(3 * numFaces_);
    for (size_t i = 0; i < edges_.size(); ++i) {
      const Edge& e = edges_[i];
      if (!e.joined || cut_.count(static_cast<int>(i))) continue;
      const int f = e.faces[0], g = e.faces[1];
      faces.join(f, g);
      for (int v : {e.a, e.b}) corners.join(3 * f + cornerOf(f, v), 3 * g + cornerOf(g, v));
    }
    piece_ = faces.labels(numPieces_);
    cornerClass_ = corners.labels(numClasses_);
  }

  /// A vertex a piece holds twice, or -1.
  std::vector<int> doubledVertexOfPieces() const {
    std::vector<int> doubled(numPieces_, -1);
    std::unordered_map<std::uint64_t, int> classOf;  // (piece, vertex) -> class
    for (int f = 0; f < numFaces_; ++f) {
      for (int k = 0; k < 3; ++k) {
        const int v = mesh_.F(f, k), c = cornerClass_[3 * f + k];
        auto [it, inserted] = classOf.emplace((static_cast<std::uint64_t>(piece_[f]) << 32) | v, c);
        if (!inserted && it->second != c && doubled[piece_[f]] < 0) doubled[piece_[f]] = v;
      }
    }
    return doubled;
  }

  void cutIslands() {
    std::vector<int> cutsOfIsland(numIslands_, 0);
    for (int round = 0;; ++round) {
      findPieces();
      const std::vector<int> doubled = doubledVertexOfPieces();
      int piece = 0;
      while (piece < numPieces_ && doubled[piece] < 0) ++piece;
      if (piece == numPieces_) break;
      std::vector<int> faces;
      for (int f = 0; f < numFaces_; ++f)
        if (piece_[f] == piece) faces.push_back(f);
      const int island = island_[faces.front()];
      PIXELCLOTH_CHECK(round < kMaxCuts, file_ << ": " << islandWhere(island) << " still holds vertex "
                                               << doubled[piece] + 1 << " twice after " << kMaxCuts
                                               << " cuts; expected UV islands that each hold a vertex once, or tubes "
                                               << "cut once along a seam");
      ++cutsOfIsland[island];
      if (splitAlongGroups(faces)) {
        islandNotes_.emplace_back(island, "holds vertex " + std::to_string(doubled[piece] + 1) +
                                              " twice (a tube): split along its " + groups_.keyword + " groups");
        continue;
      }
      const int pathEdges = cutThroughMiddle(faces, island, doubled[piece]);
      islandNotes_.emplace_back(island, "holds vertex " + std::to_string(doubled[piece] + 1) +
                                            " twice (a tube): cut in two along " + std::to_string(pathEdges) +
                                            " edges through its middle");
    }
  }

  /// Cuts every UV-continuous edge between two groups inside the piece; false when the piece is one group.
  bool splitAlongGroups(const std::vector<int>& faces) {
    if (groups_.keyword.empty()) return false;
    bool any = false;
    for (int f : faces) {
      for (int k = 0; k < 3; ++k) {
        const int e = faceEdge_[3 * f + k];
        const Edge& edge = edges_[e];
        if (!edge.joined || cut_.count(e)) continue;
        if (groups_.faceGroup[edge.faces[0]] != groups_.faceGroup[edge.faces[1]]) cut_.insert(e), any = true;
      }
    }
    return any;
  }

  /// Cuts a piece that holds vertices twice along the cheapest interior edge path between the middles of the two
  /// boundary stretches farthest from the doubled vertices, staying away from them. Returns the path's edge count.
  int cutThroughMiddle(const std::vector<int>& faces, int island, int doubledVertex) {
    // Local vertices: the corner classes of the piece.
    std::unordered_map<int, int> local;
    std::vector<int> vertexOf;
    auto localOf = [&](int f, int k) {
      auto [it, inserted] = local.emplace(cornerClass_[3 * f + k], static_cast<int>(vertexOf.size()));
      if (inserted) vertexOf.push_back(mesh_.F(f, k));
      return it->second;
    };
    struct LocalEdge {
      int count = 0;
      int edge = -1;  // mesh edge
      int face = -1;  // a face of the piece on it
    };
    std::map<std::pair<int, int>, LocalEdge> localEdges;
    std::map<std::pair<int, int>, int> directed;  // (from, to) of each face's edges -> mesh edge
    for (int f : faces) {
      int l[3];
      for (int k = 0; k < 3; ++k) l[k] = localOf(f, k);
      for (int k = 0; k < 3; ++k) {
        const int a = l[k], b = l[(k + 1) % 3];
        LocalEdge& e = localEdges[{std::min(a, b), std::max(a, b)}];
        ++e.count;
        e.edge = faceEdge_[3 * f + k];
        e.face = f;
        directed[{a, b}] = faceEdge_[3 * f + k];
      }
    }
    const int n = static_cast<int>(vertexOf.size());
    std::vector<std::vector<std::pair<int, double>>> interiorNeighbours(n), allNeighbours(n);
    std::vector<bool> boundary(n, false);
    auto length3 = [&](int a, int b) { return (mesh_.V.row(vertexOf[a]) - mesh_.V.row(vertexOf[b])).norm(); };
    for (const auto& [key, e] : localEdges) {
      const double length = length3(key.first, key.second);
      allNeighbours[key.first].emplace_back(key.second, length);
      allNeighbours[key.second].emplace_back(key.first, length);
      if (e.count == 2) {
        interiorNeighbours[key.first].emplace_back(key.second, length);
        interiorNeighbours[key.second].emplace_back(key.first, length);
      } else {
        boundary[key.first] = boundary[key.second] = true;
      }
    }
    // Sources: local vertices whose vertex the piece holds twice; distance from them along edges.
    std::unordered_map<int, int> copies;
    for (int v : vertexOf) ++copies[v];
    std::vector<double> distance(n, std::numeric_limits<double>::infinity());
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (int i = 0; i < n; ++i) {
      if (copies[vertexOf[i]] > 1) distance[i] = 0, queue.emplace(0.0, i);
    }
    while (!queue.empty()) {
      auto [d, i] = queue.top();
      queue.pop();
      if (d > distance[i]) continue;
      for (auto [j, length] : allNeighbours[i]) {
        if (d + length < distance[j]) distance[j] = d + length, queue.emplace(d + length, j);
      }
    }
    // Boundary loops of the piece and their stretches between doubled vertices.
    std::vector<int> next(n, -1);
    for (const auto& [key, edge] : directed) {
      if (!directed.count({key.second, key.first})) next[key.first] = key.second;
    }
    // What lies across each boundary edge leaving a local vertex: another island / group, or nothing.
    auto acrossOf = [&](int from) {
      const Edge& e = edges_[directed.at({from, next[from]})];
      if (e.count == 1) return -1;
      const int other = piece_[e.faces[0]] == piece_[faces.front()] ? e.faces[1] : e.faces[0];
      const int group = groups_.keyword.empty() ? 0 : groups_.faceGroup[other] + 1;
      return island_[other] * (static_cast<int>(groups_.names.size()) + 1) + group;
    };
    struct Stretch {
      int vertex = -1;  // the chosen end of the cut
      double score = -1;
    };
    std::vector<Stretch> stretches;
    std::vector<bool> seen(n, false);
    for (int start = 0; start < n; ++start) {
      if (next[start] < 0 || seen[start]) continue;
      std::vector<int> loop;
      for (int v = start; v >= 0 && !seen[v]; v = next[v]) seen[v] = true, loop.push_back(v);
      const int size = static_cast<int>(loop.size());
      int first = 0;
      while (first < size && distance[loop[first]] > 0) ++first;
      if (first == size) {  // no doubled vertex on this loop: the whole loop is one stretch, its farthest vertex
        Stretch s;
        for (int v : loop)
          if (distance[v] > s.score) s.score = distance[v], s.vertex = v;
        stretches.push_back(s);
        continue;
      }
      // Runs of vertices with distance > 0 between doubled ones, each with the doubled vertices that bound it.
      for (int i = 0; i < size;) {
        const int at = (first + i) % size;
        if (distance[loop[at]] == 0) {
          ++i;
          continue;
        }
        std::vector<int> run = {loop[(at + size - 1) % size]};
        while (i < size && distance[loop[(first + i) % size]] > 0) run.push_back(loop[(first + i) % size]), ++i;
        run.push_back(loop[(first + i) % size]);
        std::vector<double> position(run.size(), 0.0);
        for (size_t r = 1; r < run.size(); ++r) position[r] = position[r - 1] + length3(run[r - 1], run[r]);
        const double half = position.back() / 2;
        size_t middle = 1;
        for (size_t r = 1; r + 1 < run.size(); ++r)
          if (std::abs(position[r] - half) < std::abs(position[middle] - half)) middle = r;
        // Prefer a vertex nearby where the neighbour across the boundary changes (a shoulder point).
        size_t best = middle;
        double bestOffset = kCutSnapFraction * position.back();
        for (size_t r = 1; r + 1 < run.size(); ++r) {
          const int before = run[r - 1];
          if (next[before] != run[r] || next[run[r]] < 0) continue;
          if (acrossOf(before) == acrossOf(run[r])) continue;
          const double offset = std::abs(position[r] - half);
          if (offset <= bestOffset) bestOffset = offset, best = r;
        }
        stretches.push_back({run[best], distance[run[best]]});
      }
    }
    std::sort(stretches.begin(), stretches.end(), [](const Stretch& a, const Stretch& b) { return a.score > b.score; });
    PIXELCLOTH_CHECK(stretches.size() >= 2 && stretches[1].score > 0,
                     file_ << ": " << islandWhere(island) << " holds vertex " << doubledVertex + 1
                           << " twice, and its UV outline has no two stretches away from the doubled vertices to cut "
                           << "it between; expected each UV island to hold a vertex once, or a tube cut once along "
                           << "a seam (a sleeve cut along its underarm)");
    const int source = stretches[0].vertex, target = stretches[1].vertex;
    // Cheapest path through the interior, edges costing more the nearer they run to the doubled vertices.
    const double far = *std::max_element(distance.begin(), distance.end(), [](double a, double b) {
      return (std::isfinite(a) ? a : 0) < (std::isfinite(b) ? b : 0);
    });
    std::vector<double> cost(n, std::numeric_limits<double>::infinity());
    std::vector<int> previous(n, -1);
    cost[source] = 0;
    queue.emplace(0.0, source);
    while (!queue.empty()) {
      auto [c, i] = queue.top();
      queue.pop();
      if (c > cost[i]) continue;
      if (i == target) break;
      if (i != source && boundary[i]) continue;
      for (auto [j, length] : interiorNeighbours[i]) {
        if (boundary[j] && j != target) continue;
        const double mean = 0.5 * (std::min(distance[i], far) + std::min(distance[j], far));
        const double penalty = far / std::max(mean, 0.05 * far);
        const double step = c + length * penalty * penalty;
        if (step < cost[j]) cost[j] = step, previous[j] = i, queue.emplace(step, j);
      }
    }
    PIXELCLOTH_CHECK(previous[target] >= 0,
                     file_ << ": " << islandWhere(island) << " holds vertex " << doubledVertex + 1
                           << " twice, and no path of interior edges joins vertex " << vertexOf[source] + 1
                           << " and vertex " << vertexOf[target] + 1
                           << " across it to cut it in two; expected each UV island to hold a vertex once, or a "
                              "tube cut once along a seam");
    int count = 0;
    for (int j = target; j != source; j = previous[j], ++count) {
      const int i = previous[j];
      cut_.insert(localEdges.at({std::min(i, j), std::max(i, j)}).edge);
    }
    return count;
  }

  // -------------------------------------------------------------------------------------------------------------------
  // Panels, UVs, seams

  void findPanels() {
    Components components(numFaces_);
    for (const Edge& e : edges_) {
      if (e.count != 2) continue;
      const int f = e.faces[0], g = e.faces[1];
      if (piece_[f] != piece_[g]) continue;
      if (!groups_.keyword.empty() && groups_.faceGroup[f] != groups_.faceGroup[g]) continue;
      components.join(f, g);
    }
    panel_ = components.labels(numPanels_);
  }

  /// One UV per (layout, vertex): the layouts are the pieces.
  void buildUVs() {
    vertexUV_ = Eigen::MatrixXi::Constant(numVertices_, numPieces_, -1);
    std::vector<Eigen::Vector2d> rows;
    for (int f = 0; f < numFaces_; ++f) {
      for (int k = 0; k < 3; ++k) {
        int& row = vertexUV_(mesh_.F(f, k), piece_[f]);
        if (row >= 0) continue;
        row = static_cast<int>(rows.size());
        rows.emplace_back(cornerUV_.row(3 * f + k).transpose());
      }
    }
    uv_.resize(static_cast<int>(rows.size()), 2);
    for (size_t i = 0; i < rows.size(); ++i) uv_.row(static_cast<int>(i)) = rows[i].transpose();
  }

  Eigen::Vector2d uvOf(int vertex, int layout) const { return uv_.row(vertexUV_(vertex, layout)).transpose(); }

  bool isSeamEdge(const Edge& e) const { return e.count == 2 && panel_[e.faces[0]] != panel_[e.faces[1]]; }

  /// Turning of a chain at each vertex in UV (the larger of its two sides), degrees: `windowed` over about
  /// kCornerWindow of outline on each side, `step` between its two edges alone.
  void turning(const std::vector<int>& chain, bool closed, int layoutA, int layoutB, std::vector<double>& windowed,
               std::vector<double>& step) const {
    const int size = static_cast<int>(chain.size());
    windowed.assign(size, 0.0);
    step.assign(size, 0.0);
    auto angle = [](const Eigen::Vector2d& in, const Eigen::Vector2d& out) {
      if (in.norm() == 0 || out.norm() == 0) return 0.0;
      return std::atan2(std::abs(cross2(in, out)), in.dot(out)) * 180.0 / M_PI;
    };
    for (int layout : {layoutA, layoutB}) {
      for (int i = closed ? 0 : 1; i < (closed ? size : size - 1); ++i) {
        const Eigen::Vector2d at = uvOf(chain[i], layout);
        auto reach = [&](int direction) {
          Eigen::Vector2d end = at;
          double walked = 0;
          for (int s = 1; s < size; ++s) {
            const int j = i + direction * s;
            if (!closed && (j < 0 || j >= size)) break;
            end = uvOf(chain[((j % size) + size) % size], layout);
            walked = (end - at).norm();
            if (walked >= kCornerWindow) break;
          }
          return end;
        };
        const Eigen::Vector2d before = reach(-1), after = reach(1);
        windowed[i] = std::max(windowed[i], angle(at - before, after - at));
        const Eigen::Vector2d previous = uvOf(chain[(i + size - 1) % size], layout);
        const Eigen::Vector2d next = uvOf(chain[(i + 1) % size], layout);
        step[i] = std::max(step[i], angle(at - previous, next - at));
      }
    }
  }

  /// Indices of a chain's sharp corners: runs of vertices turning by more than kCornerDegrees, one vertex per run.
  std::vector<int> corners(const std::vector<int>& chain, bool closed, int layoutA, int layoutB) const {
    std::vector<double> windowed, step;
    turning(chain, closed, layoutA, layoutB, windowed, step);
    const int size = static_cast<int>(chain.size());
    std::vector<bool> sharp(size);
    for (int i = 0; i < size; ++i) sharp[i] = windowed[i] > kCornerDegrees;
    int start = 0;
    if (closed) {
      while (start < size && sharp[start]) ++start;
      if (start == size) return {static_cast<int>(std::max_element(step.begin(), step.end()) - step.begin())};
    }
    std::vector<int> found;
    for (int s = 0; s < size;) {
      const int i = (start + s) % size;
      if (!sharp[i]) {
        ++s;
        continue;
      }
      int best = i;
      while (s < size && sharp[(start + s) % size]) {
        const int j = (start + s) % size;
        if (step[j] > step[best] || (step[j] == step[best] && windowed[j] > windowed[best])) best = j;
        ++s;
      }
      found.push_back(best);
    }
    std::sort(found.begin(), found.end());
    return found;
  }

  void findSeams() {
    std::vector<std::vector<int>> neighbours(numVertices_);
    std::set<std::uint64_t> unvisited;
    for (const Edge& e : edges_) {
      if (!isSeamEdge(e)) continue;
      neighbours[e.a].push_back(e.b);
      neighbours[e.b].push_back(e.a);
      unvisited.insert(edgeKey(e.a, e.b));
    }
    std::vector<bool> junction(numVertices_, false);
    for (int v = 0; v < numVertices_; ++v) {
      if (neighbours[v].empty()) continue;
      std::set<int> panels;
      for (int f : vertexFaces_[v]) panels.insert(panel_[f]);
      junction[v] = neighbours[v].size() != 2 || panels.size() >= 3 || onBoundary_[v];
    }
    std::vector<std::pair<std::vector<int>, bool>> raw;  // chain, closed
    auto walk = [&](int from, int to) {
      std::vector<int> chain = {from, to};
      unvisited.erase(edgeKey(from, to));
      int previous = from, current = to;
      while (!junction[current] && current != from) {
        int next = -1;
        for (int n : neighbours[current])
          if (n != previous && unvisited.count(edgeKey(current, n))) next = n;
        if (next < 0) break;
        unvisited.erase(edgeKey(current, next));
        previous = current;
        current = next;
        chain.push_back(current);
      }
      return chain;
    };
    for (int v = 0; v < numVertices_; ++v) {
      if (!junction[v]) continue;
      for (int n : neighbours[v])
        if (unvisited.count(edgeKey(v, n))) raw.emplace_back(walk(v, n), false);
    }
    while (!unvisited.empty()) {  // loops with no junction
      const std::uint64_t key = *unvisited.begin();
      std::vector<int> chain = walk(static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu));
      PIXELCLOTH_ASSERT(chain.front() == chain.back(), "a seam loop does not close");
      chain.pop_back();
      raw.emplace_back(std::move(chain), true);
    }
    for (auto& [chain, closed] : raw) {
      const Edge& first = edges_[edgeIndex_.at(edgeKey(chain[0], chain[1]))];
      const int layoutA = piece_[first.faces[0]], layoutB = piece_[first.faces[1]];
      std::vector<int> split = corners(chain, closed, layoutA, layoutB);
      if (closed) {
        // A loop needs two ends at least: the highest vertex, or a corner, and the vertex half-way round from it.
        if (split.empty()) {
          int top = 0;
          for (int i = 1; i < static_cast<int>(chain.size()); ++i)
            if (mesh_.V(chain[i], 1) > mesh_.V(chain[top], 1)) top = i;
          split.push_back(top);
        }
        if (split.size() == 1) split.push_back((split[0] + static_cast<int>(chain.size()) / 2) % chain.size());
        std::sort(split.begin(), split.end());
        for (size_t s = 0; s < split.size(); ++s) {
          const int from = split[s], to = split[(s + 1) % split.size()];
          std::vector<int> piece;
          for (int i = from;; i = (i + 1) % chain.size()) {
            piece.push_back(chain[i]);
            if (i == to && piece.size() > 1) break;
          }
          addChain(piece);
        }
        continue;
      }
      int from = 0;
      split.push_back(static_cast<int>(chain.size()) - 1);
      for (int to : split) {
        if (to <= from) continue;
        addChain(std::vector<int>(chain.begin() + from, chain.begin() + to + 1));
        from = to;
      }
    }
  }

  void addChain(std::vector<int> vertices) {
    Chain chain;
    const Edge& first = edges_[edgeIndex_.at(edgeKey(vertices[0], vertices[1]))];
    for (int s = 0; s < 2; ++s) chain.panels[s] = panel_[first.faces[s]], chain.layouts[s] = piece_[first.faces[s]];
    for (size_t i = 0; i + 1 < vertices.size(); ++i) {
      const Eigen::Vector3d p = mesh_.V.row(vertices[i]), q = mesh_.V.row(vertices[i + 1]);
      chain.length += (q - p).norm();
      chain.centroid += (q - p).norm() * 0.5 * (p + q);
    }
    chain.centroid /= std::max(chain.length, 1e-300);
    chain.vertices = std::move(vertices);
    chains_.push_back(std::move(chain));
  }

  // -------------------------------------------------------------------------------------------------------------------
  // Names

  bool loopTouchesPanel(const Loop& loop, int panel) const {
    for (size_t i = 0; i < loop.vertices.size(); ++i) {
      const Edge& e = edges_[edgeIndex_.at(edgeKey(loop.vertices[i], loop.vertices[(i + 1) % loop.vertices.size()]))];
      if (panel_[e.faces[0]] == panel) return true;
    }
    return false;
  }

  /// Openings: hem, neckline or waist, sleeve hems, leg hems, outline, by where each loop sits.
  void nameOpenings() {
    const double centre = centroid_.x(), middle = box_.center().y();
    std::vector<int> order(loops_.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return loops_[a].centroid.y() < loops_[b].centroid.y(); });
    if (loops_.size() == 1) {
      loops_[0].name = "outline";
      return;
    }
    std::vector<int> around;  // loops around the centre line, lowest first
    for (int l : order)
      if (loops_[l].box.min().x() < centre && loops_[l].box.max().x() > centre) around.push_back(l);
    hem_ = -1;
    top_ = -1;
    if (!around.empty() && loops_[around.front()].centroid.y() < middle)
      hem_ = around.front(), loops_[hem_].name = "hem";
    if (!around.empty() && around.back() != hem_ && loops_[around.back()].centroid.y() > middle) {
      top_ = around.back();
      const Loop& top = loops_[top_];
      // A neckline is narrower than the garment at its height (shoulders beside it); a waist is as wide.
      const double band = 0.02 * box_.sizes().y();
      double low = std::numeric_limits<double>::infinity(), high = -low;
      for (int v = 0; v < numVertices_; ++v) {
        const double y = mesh_.V(v, 1);
        if (y < top.box.min().y() - band || y > top.box.max().y()) continue;
        low = std::min(low, mesh_.V(v, 0));
        high = std::max(high, mesh_.V(v, 0));
      }
      loops_[top_].name = top.box.sizes().x() < 0.7 * (high - low) ? "neckline" : "waist";
    }
    for (int side = 0; side < 2; ++side) {  // 0: the wearer's left, +x
      int best = -1;
      for (size_t l = 0; l < loops_.size(); ++l) {
        const Loop& loop = loops_[l];
        if (!loop.name.empty() || (loop.centroid.x() > centre) != (side == 0)) continue;
        if (loop.box.min().x() < centre && loop.box.max().x() > centre) continue;
        if (hem_ >= 0) {
          if (loop.centroid.y() <= loops_[hem_].centroid.y()) continue;
          if (best < 0 || std::abs(loop.centroid.x() - centre) > std::abs(loops_[best].centroid.x() - centre))
            best = static_cast<int>(l);
        } else {
          if (loop.centroid.y() >= middle) continue;
          if (best < 0 || loop.centroid.y() < loops_[best].centroid.y()) best = static_cast<int>(l);
        }
      }
      if (best < 0) continue;
      loops_[best].name = std::string(hem_ >= 0 ? "sleeve_hem_" : "leg_hem_") + (side == 0 ? "left" : "right");
      sleeveHems_[side] = hem_ >= 0 ? best : -1;
    }
    std::set<std::string> taken;
    for (const Loop& loop : loops_) taken.insert(loop.name);
    int counter = 0;
    for (int l : order) {
      if (!loops_[l].name.empty()) continue;
      std::string name;
      do name = "opening_" + std::to_string(++counter);
      while (taken.count(name));
      loops_[l].name = name;
      taken.insert(name);
    }
  }

  /// Panels: front / back (touching the hem or the top opening), sleeves (reached from a sleeve hem), the rest.
  void namePanels() {
    role_.assign(numPanels_, Role::Other);
    side_.assign(numPanels_, -1);
    normalZ_.assign(numPanels_, 0.0);
    std::vector<double> area(numPanels_, 0.0), centreX(numPanels_, 0.0);
    for (int f = 0; f < numFaces_; ++f) {
      const Eigen::Vector3d n = 0.5 * faceNormalTimesTwiceArea(f);
      normalZ_[panel_[f]] += n.z();
      area[panel_[f]] += n.norm();
      centreX[panel_[f]] += n.norm() * faceCentroid(f).x();
    }
    for (int p = 0; p < numPanels_; ++p) {
      if (area[p] > 0) normalZ_[p] /= area[p], centreX[p] /= area[p];
    }
    panelNames_.assign(numPanels_, "");
    panelArea_ = area;
    if (numPanels_ == 1) {
      panelNames_[0] = name_;
      return;
    }
    for (int l : {hem_, top_}) {
      if (l < 0) continue;
      for (int p = 0; p < numPanels_; ++p)
        if (loopTouchesPanel(loops_[l], p)) role_[p] = Role::Torso;
    }
    std::vector<std::set<int>> adjacent(numPanels_);
    for (const Chain& c : chains_) adjacent[c.panels[0]].insert(c.panels[1]), adjacent[c.panels[1]].insert(c.panels[0]);
    std::vector<int> reached(numPanels_, 0);  // bit 1: from the left sleeve hem, bit 2: from the right
    for (int side = 0; side < 2; ++side) {
      if (sleeveHems_[side] < 0) continue;
      std::vector<int> stack;
      for (int p = 0; p < numPanels_; ++p)
        if (role_[p] != Role::Torso && loopTouchesPanel(loops_[sleeveHems_[side]], p)) stack.push_back(p);
      while (!stack.empty()) {
        const int p = stack.back();
        stack.pop_back();
        if (reached[p] & (1 << side)) continue;
        reached[p] |= 1 << side;
        for (int q : adjacent[p])
          if (role_[q] != Role::Torso) stack.push_back(q);
      }
    }
    for (int p = 0; p < numPanels_; ++p) {
      if (reached[p] == 1 || reached[p] == 2) role_[p] = Role::Sleeve, side_[p] = reached[p] == 1 ? 0 : 1;
    }
    std::set<std::string> taken;
    auto assign = [&](std::vector<int> members, const std::string& single, const std::string& first,
                      const std::string& second, const std::string& numbered) {
      if (members.empty()) return;
      if (members.size() == 1) {
        panelNames_[members[0]] = single;
      } else if (members.size() == 2) {
        panelNames_[members[0]] = first;
        panelNames_[members[1]] = second;
      } else {
        for (size_t i = 0; i < members.size(); ++i) panelNames_[members[i]] = numbered + std::to_string(i + 1);
      }
      for (int p : members) taken.insert(panelNames_[p]);
    };
    for (bool front : {true, false}) {
      std::vector<int> members;
      for (int p = 0; p < numPanels_; ++p)
        if (role_[p] == Role::Torso && (normalZ_[p] >= 0) == front) members.push_back(p);
      std::sort(members.begin(), members.end(), [&](int a, int b) { return centreX[a] < centreX[b]; });
      const std::string base = front ? "front" : "back";
      assign(members, base, base + "_right", base + "_left", base + "_");
    }
    for (int side = 0; side < 2; ++side) {
      std::vector<int> members;
      for (int p = 0; p < numPanels_; ++p)
        if (role_[p] == Role::Sleeve && side_[p] == side) members.push_back(p);
      std::sort(members.begin(), members.end(), [&](int a, int b) { return normalZ_[a] > normalZ_[b]; });
      const std::string base = side == 0 ? "left_sleeve" : "right_sleeve";
      assign(members, base, base + "_front", base + "_back", base + "_");
    }
    for (int p = 0; p < numPanels_; ++p) {
      if (!panelNames_[p].empty()) continue;
      std::string name;
      if (!groups_.keyword.empty()) {
        for (int f = 0; f < numFaces_ && name.empty(); ++f)
          if (panel_[f] == p) name = sanitized(groups_.names[groups_.faceGroup[f]]);
      }
      if (name.empty() || taken.count(name)) {
        int counter = p + 1;
        do name = "panel_" + std::to_string(counter++);
        while (taken.count(name));
      }
      panelNames_[p] = name;
      taken.insert(name);
    }
  }

  bool chainTouches(const Chain& chain, int loop) const {
    if (loop < 0) return false;
    const std::vector<int>& vertices = loops_[loop].vertices;
    for (int v : {chain.vertices.front(), chain.vertices.back()})
      if (std::find(vertices.begin(), vertices.end(), v) != vertices.end()) return true;
    return false;
  }

  /// Mean normal z of the faces of `panel` along a chain.
  double normalZAlong(const Chain& chain, int panel) const {
    double z = 0;
    for (size_t i = 0; i + 1 < chain.vertices.size(); ++i) {
      const Edge& e = edges_[edgeIndex_.at(edgeKey(chain.vertices[i], chain.vertices[i + 1]))];
      for (int f : e.faces)
        if (f >= 0 && panel_[f] == panel) z += faceNormalTimesTwiceArea(f).normalized().z();
    }
    return z;
  }

  void nameSeams() {
    const double centre = centroid_.x();
    std::vector<int> order(chains_.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return chains_[a].length > chains_[b].length; });
    std::set<std::string> taken;
    auto propose = [&](Chain& chain, const std::string& name) {
      if (taken.insert(name).second) chain.name = name;
    };
    // Candidates for sleeve_top / underarm per side: front-to-back seams ending on that sleeve hem.
    std::array<std::vector<int>, 2> sleeveSeams;
    for (int c : order) {
      Chain& chain = chains_[c];
      const int p = chain.panels[0], q = chain.panels[1];
      const std::string hand = chain.centroid.x() > centre ? "left" : "right";
      const Role rp = role_[p], rq = role_[q];
      if (rp == Role::Torso && rq == Role::Torso && (normalZ_[p] >= 0) != (normalZ_[q] >= 0)) {
        if (chainTouches(chain, hem_)) {
          propose(chain, "side_" + hand);
        } else if (top_ >= 0 && loops_[top_].name == "neckline" && chainTouches(chain, top_)) {
          propose(chain, "shoulder_" + hand);
        } else {
          for (int side = 0; side < 2; ++side)
            if (chainTouches(chain, sleeveHems_[side])) sleeveSeams[side].push_back(c);
        }
      } else if ((rp == Role::Torso && rq == Role::Sleeve) || (rp == Role::Sleeve && rq == Role::Torso)) {
        const int torso = rp == Role::Torso ? p : q, sleeve = rp == Role::Torso ? q : p;
        const std::string part = normalZAlong(chain, torso) >= 0 ? "front" : "back";
        propose(chain, "armhole_" + part + "_" + (side_[sleeve] == 0 ? "left" : "right"));
      } else if (rp == Role::Sleeve && rq == Role::Sleeve && side_[p] == side_[q]) {
        if (chainTouches(chain, sleeveHems_[side_[p]])) sleeveSeams[side_[p]].push_back(c);
      }
    }
    for (int side = 0; side < 2; ++side) {
      std::vector<int>& list = sleeveSeams[side];
      if (list.empty()) continue;
      std::sort(list.begin(), list.end(),
                [&](int a, int b) { return chains_[a].centroid.y() > chains_[b].centroid.y(); });
      const std::string hand = side == 0 ? "left" : "right";
      if (list.size() == 1) {
        const bool above = chains_[list[0]].centroid.y() >= loops_[sleeveHems_[side]].centroid.y();
        propose(chains_[list[0]], (above ? "sleeve_top_" : "underarm_") + hand);
      } else {
        propose(chains_[list.front()], "sleeve_top_" + hand);
        propose(chains_[list.back()], "underarm_" + hand);
      }
    }
    int counter = 0;
    for (Chain& chain : chains_) {
      ++counter;
      if (!chain.name.empty()) continue;
      std::string name;
      int n = counter;
      do name = "seam_" + std::to_string(n++);
      while (taken.count(name));
      chain.name = name;
      taken.insert(name);
    }
    // Directions as the templates run them: side seams and armholes from the top; shoulders, sleeve tops and
    // underarms from the centre line outwards.
    for (Chain& chain : chains_) {
      const Eigen::Vector3d first = mesh_.V.row(chain.vertices.front()), last = mesh_.V.row(chain.vertices.back());
      bool reverse = false;
      if (chain.name.rfind("side_", 0) == 0 || chain.name.rfind("armhole_", 0) == 0) {
        reverse = last.y() > first.y();
      } else if (chain.name.rfind("shoulder_", 0) == 0 || chain.name.rfind("sleeve_top_", 0) == 0 ||
                 chain.name.rfind("underarm_", 0) == 0) {
        reverse = std::abs(last.x() - centre) < std::abs(first.x() - centre);
      }
      if (reverse) std::reverse(chain.vertices.begin(), chain.vertices.end());
    }
  }

  std::string islandLabel(int island) const {
    std::vector<std::string> names;
    for (int f : islandFaces_[island]) {
      const std::string& name = layoutNames_[piece_[f]];
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
    std::string label;
    if (names.size() > 1) {  // the common prefix of its layouts' names ("left_sleeve"), else all of them
      std::string prefix = names[0];
      for (const std::string& n : names) {
        size_t k = 0;
        while (k < prefix.size() && k < n.size() && prefix[k] == n[k]) ++k;
        prefix.resize(k);
      }
      while (!prefix.empty() && prefix.back() == '_') prefix.pop_back();
      if (!prefix.empty()) label = prefix;
      for (size_t i = 0; label.empty() && i < names.size(); ++i) label += (i ? "+" : "") + names[i];
      if (label.empty())
        for (size_t i = 0; i < names.size(); ++i) label += (i ? "+" : "") + names[i];
    } else {
      label = names[0];
    }
    return "island " + std::to_string(island + 1) + " (" + label + ")";
  }

  // -------------------------------------------------------------------------------------------------------------------
  // The garment

  Garment assemble() {
    // Layouts after their largest panel.
    layoutNames_.assign(numPieces_, "");
    std::vector<double> largest(numPieces_, -1), layoutArea(numPieces_, 0.0);
    std::vector<int> panelLayout(numPanels_, -1);
    for (int f = 0; f < numFaces_; ++f) panelLayout[panel_[f]] = piece_[f];
    for (int p = 0; p < numPanels_; ++p) {
      const int l = panelLayout[p];
      layoutArea[l] += panelArea_[p];
      if (panelArea_[p] > largest[l]) largest[l] = panelArea_[p], layoutNames_[l] = panelNames_[p];
    }
    // Panels and layouts in the templates' order (front first: Garment::length() measures the first layout), the
    // rest largest first.
    const std::vector<std::string> panelOrder = {"front",
                                                 "back",
                                                 "front_right",
                                                 "front_left",
                                                 "back_right",
                                                 "back_left",
                                                 "left_sleeve",
                                                 "left_sleeve_front",
                                                 "left_sleeve_back",
                                                 "right_sleeve",
                                                 "right_sleeve_front",
                                                 "right_sleeve_back"};
    auto rank = [](const std::vector<std::string>& known, const std::string& name) {
      return static_cast<int>(std::find(known.begin(), known.end(), name) - known.begin());
    };
    auto order = [&](int count, const std::vector<std::string>& names, const std::vector<double>& area) {
      std::vector<int> sorted(count), index(count);
      std::iota(sorted.begin(), sorted.end(), 0);
      std::stable_sort(sorted.begin(), sorted.end(), [&](int a, int b) {
        const int ra = rank(panelOrder, names[a]), rb = rank(panelOrder, names[b]);
        return ra != rb ? ra < rb : area[a] > area[b];
      });
      for (int i = 0; i < count; ++i) index[sorted[i]] = i;
      return index;  // new index of each old one
    };
    const std::vector<int> newPanel = order(numPanels_, panelNames_, panelArea_);
    const std::vector<int> newLayout = order(numPieces_, layoutNames_, layoutArea);

    Garment garment;
    garment.name = name_;
    garment.mesh.V = mesh_.V;
    garment.mesh.F = mesh_.F;
    garment.panels.resize(numPanels_);
    for (int p = 0; p < numPanels_; ++p) garment.panels[newPanel[p]] = panelNames_[p];
    garment.layouts.resize(numPieces_);
    for (int l = 0; l < numPieces_; ++l) garment.layouts[newLayout[l]] = layoutNames_[l];
    garment.facePanel.resize(numFaces_);
    garment.faceLayout.resize(numFaces_);
    for (int f = 0; f < numFaces_; ++f) {
      garment.facePanel[f] = newPanel[panel_[f]];
      garment.faceLayout[f] = newLayout[piece_[f]];
    }
    // UV rows layout by layout, each layout's vertices in order.
    garment.vertexUV = Eigen::MatrixXi::Constant(numVertices_, numPieces_, -1);
    int rows = 0;
    for (int l = 0; l < numPieces_; ++l) {
      const int old = static_cast<int>(std::find(newLayout.begin(), newLayout.end(), l) - newLayout.begin());
      for (int v = 0; v < numVertices_; ++v)
        if (vertexUV_(v, old) >= 0) garment.vertexUV(v, l) = rows++;
    }
    garment.mesh.UV.resize(rows, 2);
    for (int l = 0; l < numPieces_; ++l) {
      const int old = static_cast<int>(std::find(newLayout.begin(), newLayout.end(), l) - newLayout.begin());
      for (int v = 0; v < numVertices_; ++v)
        if (vertexUV_(v, old) >= 0) garment.mesh.UV.row(garment.vertexUV(v, l)) = uv_.row(vertexUV_(v, old));
    }
    garment.mesh.FUV.resize(numFaces_, 3);
    for (int f = 0; f < numFaces_; ++f)
      for (int k = 0; k < 3; ++k) garment.mesh.FUV(f, k) = garment.vertexUV(mesh_.F(f, k), garment.faceLayout[f]);

    const std::vector<std::string> seamOrder = {"side_left",           "side_right",        "underarm_left",
                                                "underarm_right",      "shoulder_left",     "shoulder_right",
                                                "sleeve_top_left",     "sleeve_top_right",  "armhole_front_left",
                                                "armhole_front_right", "armhole_back_left", "armhole_back_right"};
    std::vector<int> seams(chains_.size());
    std::iota(seams.begin(), seams.end(), 0);
    std::stable_sort(seams.begin(), seams.end(),
                     [&](int a, int b) { return rank(seamOrder, chains_[a].name) < rank(seamOrder, chains_[b].name); });
    for (int c : seams) {
      const Chain& chain = chains_[c];
      garment.seams.push_back(Seam{chain.name, chain.vertices, chain.layouts[0] != chain.layouts[1]});
    }
    const std::vector<std::string> openingOrder = {
        "hem", "neckline", "waist", "sleeve_hem_left", "sleeve_hem_right", "leg_hem_left", "leg_hem_right"};
    std::vector<int> openings(loops_.size());
    std::iota(openings.begin(), openings.end(), 0);
    std::stable_sort(openings.begin(), openings.end(), [&](int a, int b) {
      return rank(openingOrder, loops_[a].name) < rank(openingOrder, loops_[b].name);
    });
    for (int l : openings) garment.openings.push_back(Opening{loops_[l].name, loops_[l].vertices});
    return garment;
  }

  fs::path path_;
  std::string file_, name_;
  ObjImportOptions options_;
  core::Mesh mesh_;
  int numVertices_ = 0, numFaces_ = 0;
  FaceGroups groups_;
  Eigen::MatrixX2d cornerUV_;  // 3 #F x 2: the UV of corner k of face f at row 3 f + k, fixed per island
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();  // area-weighted, of the surface
  Eigen::AlignedBox3d box_;
  std::vector<Edge> edges_;
  std::unordered_map<std::uint64_t, int> edgeIndex_;
  std::vector<int> faceEdge_;  // 3 #F: edge of face f from corner k to k + 1
  std::vector<std::vector<int>> vertexFaces_;
  std::vector<bool> onBoundary_;
  std::vector<Loop> loops_;
  int hem_ = -1, top_ = -1;
  int sleeveHems_[2] = {-1, -1};  // the wearer's left, right
  std::vector<int> island_;
  int numIslands_ = 0;
  std::vector<std::vector<int>> islandFaces_;
  std::set<int> cut_;  // edges cut to split islands holding a vertex twice
  std::vector<int> piece_, cornerClass_;
  int numPieces_ = 0, numClasses_ = 0;
  std::vector<int> panel_;
  int numPanels_ = 0;
  Eigen::MatrixXi vertexUV_;
  Eigen::MatrixX2d uv_;
  std::vector<Chain> chains_;
  std::vector<Role> role_;
  std::vector<int> side_;
  std::vector<double> normalZ_, panelArea_;
  std::vector<std::string> panelNames_, layoutNames_;
  std::vector<std::pair<int, std::string>> islandNotes_;
  std::vector<std::string> notes_;
};

}  // namespace

// ---------------------------------------------------------------------------------------------------------------------

void ObjImportOptions::validate() const {
  PIXELCLOTH_CHECK(up == 'y' || up == 'z', "OBJ import options: up must be 'y' or 'z', got '" << up << "'");
  PIXELCLOTH_CHECK(std::isfinite(scale) && scale > 0,
                   "OBJ import options: scale must be a positive number, got " << scale);
  PIXELCLOTH_CHECK(translate.allFinite(),
                   "OBJ import options: translate must be finite, got " << translate.transpose());
}

std::string ObjImportReport::summary() const {
  if (notes.empty()) return "no fixes";
  std::string out = std::to_string(notes.size()) + (notes.size() == 1 ? " fix: " : " fixes: ");
  for (size_t i = 0; i < notes.size(); ++i) out += (i ? "; " : "") + notes[i];
  return out;
}

void placeGarment(Garment& garment, const ObjImportOptions& options) {
  options.validate();
  for (int v = 0; v < garment.mesh.numVertices(); ++v) {
    const Eigen::Vector3d p = garment.mesh.V.row(v).transpose();
    garment.mesh.V.row(v) = (turnToYUp(p, options.up) * options.scale + options.translate).transpose();
  }
}

Garment importGarmentObj(const fs::path& obj, const ObjImportOptions& options, ObjImportReport* report) {
  return ObjImporter(obj, options).run(report);
}

// ---------------------------------------------------------------------------------------------------------------------
// Export

void ObjExportOptions::validate() const {
  PIXELCLOTH_CHECK(up == 'y' || up == 'z', "OBJ export options: up must be 'y' or 'z', got '" << up << "'");
  PIXELCLOTH_CHECK(std::isfinite(scale) && scale > 0,
                   "OBJ export options: scale must be a positive number, got " << scale);
  PIXELCLOTH_CHECK(std::isfinite(uvScale) && uvScale > 0,
                   "OBJ export options: uvScale must be a positive number, got " << uvScale);
  PIXELCLOTH_CHECK(translate.allFinite(),
                   "OBJ export options: translate must be finite, got " << translate.transpose());
}

void exportGarmentObj(const Garment& garment, const fs::path& obj, const ObjExportOptions& options) {
  options.validate();
  const core::Mesh& mesh = garment.mesh;
  mesh.validate(garment.name);
  PIXELCLOTH_CHECK(mesh.hasUV(), obj.string() << ": garment '" << garment.name << "' has no UVs to export");
  const int numVertices = mesh.numVertices(), numFaces = mesh.numFaces();
  auto panelIndex = [&](const std::string& name) {
    auto it = std::find(garment.panels.begin(), garment.panels.end(), name);
    return it == garment.panels.end() ? -1 : static_cast<int>(it - garment.panels.begin());
  };

  // The island of each face (a name) and the UV of each corner.
  std::vector<std::string> island(numFaces);
  Eigen::MatrixX2d cornerUV(3 * numFaces, 2);
  std::vector<int> cornerCopy(3 * numFaces, 0);  // 1: the back half of a tube sleeve, off its sleeve top
  for (int f = 0; f < numFaces; ++f) {
    island[f] = options.separatePanels ? "panel " + garment.panels[garment.facePanel[f]]
                                       : "layout " + garment.layouts[garment.faceLayout[f]];
    for (int k = 0; k < 3; ++k) cornerUV.row(3 * f + k) = mesh.UV.row(mesh.FUV(f, k));
  }
  if (options.tubeSleeves) {
    for (const std::string side : {"left", "right"}) {
      const int front = panelIndex(side + "_sleeve_front"), back = panelIndex(side + "_sleeve_back");
      const Seam* top = garment.findSeam("sleeve_top_" + side);
      PIXELCLOTH_CHECK(front >= 0 && back >= 0 && top != nullptr,
                       obj.string() << ": tube sleeves need the panels " << side << "_sleeve_front and " << side
                                    << "_sleeve_back and the seam sleeve_top_" << side << "; garment '" << garment.name
                                    << "' lacks them");
      int frontLayout = -1, backLayout = -1;
      for (int f = 0; f < numFaces; ++f) {
        if (garment.facePanel[f] == front) frontLayout = garment.faceLayout[f];
        if (garment.facePanel[f] == back) backLayout = garment.faceLayout[f];
      }
      // The rotation and shift taking the back half's sleeve top onto the front half's (2D Procrustes, no
      // reflection: both halves run counter-clockwise, so the back half lands across the line).
      std::vector<Eigen::Vector2d> from, to;
      for (int v : top->vertices) {
        PIXELCLOTH_CHECK(garment.vertexUV(v, frontLayout) >= 0 && garment.vertexUV(v, backLayout) >= 0,
                         obj.string() << ": seam sleeve_top_" << side << " does not join the sleeve's two layouts");
        from.push_back(mesh.UV.row(garment.vertexUV(v, backLayout)).transpose());
        to.push_back(mesh.UV.row(garment.vertexUV(v, frontLayout)).transpose());
      }
      Eigen::Vector2d meanFrom = Eigen::Vector2d::Zero(), meanTo = Eigen::Vector2d::Zero();
      for (size_t i = 0; i < from.size(); ++i) meanFrom += from[i] / from.size(), meanTo += to[i] / to.size();
      double dot = 0, cross = 0;
      for (size_t i = 0; i < from.size(); ++i) {
        dot += (from[i] - meanFrom).dot(to[i] - meanTo);
        cross += cross2(from[i] - meanFrom, to[i] - meanTo);
      }
      const Eigen::Rotation2Dd rotation(std::atan2(cross, dot));
      std::set<int> onTop(top->vertices.begin(), top->vertices.end());
      for (int f = 0; f < numFaces; ++f) {
        const int panel = garment.facePanel[f];
        if (panel != front && panel != back) continue;
        island[f] = "sleeve " + side;
        if (panel != back) continue;
        for (int k = 0; k < 3; ++k) {
          const int v = mesh.F(f, k);
          if (onTop.count(v)) {
            cornerUV.row(3 * f + k) = mesh.UV.row(garment.vertexUV(v, frontLayout));
          } else {
            const Eigen::Vector2d uv = cornerUV.row(3 * f + k).transpose();
            cornerUV.row(3 * f + k) = (rotation * (uv - meanFrom) + meanTo).transpose();
            cornerCopy[3 * f + k] = 1;
          }
        }
      }
    }
  }

  // Order of vertices, faces and corners in the file.
  std::vector<int> vertexOrder(numVertices), faceOrder(numFaces), firstCorner(numFaces, 0);
  std::iota(vertexOrder.begin(), vertexOrder.end(), 0);
  std::iota(faceOrder.begin(), faceOrder.end(), 0);
  if (options.shuffleSeed != 0) {
    std::mt19937 random(options.shuffleSeed);
    std::shuffle(vertexOrder.begin(), vertexOrder.end(), random);
    std::shuffle(faceOrder.begin(), faceOrder.end(), random);
    for (int& k : firstCorner) k = static_cast<int>(random() % 3);
  } else if (options.groups) {
    std::stable_sort(faceOrder.begin(), faceOrder.end(),
                     [&](int a, int b) { return garment.facePanel[a] < garment.facePanel[b]; });
  }
  std::vector<int> fileVertex(numVertices);  // 1-based number in the file
  for (int i = 0; i < numVertices; ++i) fileVertex[vertexOrder[i]] = i + 1;

  // One vt per (island, vertex, copy), numbered in order of first use; islands side by side in u.
  std::map<std::string, int> islandIndex;
  std::map<std::tuple<int, int, int>, int> texcoordOf;
  std::vector<Eigen::Vector2d> texcoords;
  std::vector<int> texcoordIsland;
  std::vector<std::array<int, 3>> faceTexcoords(numFaces);
  for (int f : faceOrder) {
    const int i = islandIndex.emplace(island[f], static_cast<int>(islandIndex.size())).first->second;
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = texcoordOf.emplace(std::make_tuple(i, mesh.F(f, k), cornerCopy[3 * f + k]),
                                               static_cast<int>(texcoords.size()));
      if (inserted) texcoords.emplace_back(cornerUV.row(3 * f + k).transpose()), texcoordIsland.push_back(i);
      faceTexcoords[f][k] = it->second;
    }
  }
  std::vector<Eigen::AlignedBox2d> boxes(islandIndex.size());
  for (size_t t = 0; t < texcoords.size(); ++t) boxes[texcoordIsland[t]].extend(texcoords[t]);
  double gap = 0;
  for (const auto& box : boxes) gap = std::max(gap, 0.05 * box.sizes().maxCoeff());
  std::vector<Eigen::Vector2d> shift(boxes.size());
  double cursor = 0;
  for (size_t i = 0; i < boxes.size(); ++i) {
    shift[i] = Eigen::Vector2d(cursor - boxes[i].min().x(), -boxes[i].min().y());
    cursor += boxes[i].sizes().x() + gap;
  }

  std::ostringstream out;
  out << std::setprecision(9);
  out << "# " << garment.name << ": " << numVertices << " vertices, " << numFaces << " faces, " << boxes.size()
      << " UV islands (pixelcloth exportGarmentObj)\n";
  for (int v : vertexOrder) {
    const Eigen::Vector3d p = turnFromYUp((mesh.V.row(v).transpose() - options.translate) / options.scale, options.up);
    out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  for (size_t t = 0; t < texcoords.size(); ++t) {
    const Eigen::Vector2d uv = (texcoords[t] + shift[texcoordIsland[t]]) * options.uvScale;
    out << "vt " << uv.x() << ' ' << uv.y() << '\n';
  }
  int group = -1;
  for (int f : faceOrder) {
    if (options.groups && garment.facePanel[f] != group) {
      group = garment.facePanel[f];
      out << "g " << garment.panels[group] << '\n';
    }
    out << 'f';
    for (int s = 0; s < 3; ++s) {
      const int k = (firstCorner[f] + s) % 3;
      out << ' ' << fileVertex[mesh.F(f, k)] << '/' << faceTexcoords[f][k] + 1;
    }
    out << '\n';
  }
  core::writeTextAtomically(obj, out.str());
}

}  // namespace pixelcloth::garment
