#include "pixelcloth/patches/patch.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/patches/frame.h"

namespace pixelcloth::patches {

namespace {
using Edge = std::pair<int, int>;
Edge key(int a, int b) { return std::minmax(a, b); }

}  // namespace

std::vector<Patch> garmentPatches(const garment::Garment& garment) {
  return segmentPatches(garment, cage::cutEdges(cage::garmentCage(garment)));
}

std::vector<Patch> segmentPatches(const garment::Garment& garment, const std::vector<std::pair<int, int>>& cuts) {
  const core::Mesh& mesh = garment.mesh;
  std::set<Edge> cutSet;
  for (const auto& [a, b] : cuts) cutSet.insert(key(a, b));
  // Faces sharing an edge, within one layout, not across a cut.
  std::map<Edge, std::vector<int>> edgeFaces;
  for (int f = 0; f < mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k) edgeFaces[key(mesh.F(f, k), mesh.F(f, (k + 1) % 3))].push_back(f);
  std::vector<int> parent(mesh.numFaces());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); };
  for (const auto& [edge, faces] : edgeFaces) {
    if (faces.size() != 2 || cutSet.count(edge)) continue;
    if (garment.faceLayout[faces[0]] != garment.faceLayout[faces[1]]) continue;
    parent[find(faces[0])] = find(faces[1]);
  }
  std::map<int, std::vector<int>> groups;
  for (int f = 0; f < mesh.numFaces(); ++f) groups[find(f)].push_back(f);

  std::vector<Patch> patches;
  for (auto& [root, faces] : groups) {
    Patch patch;
    patch.layout = garment.faceLayout[faces.front()];
    patch.faces = faces;
    // Boundary half-edges: directed edges of the patch whose twin is not in the patch.
    std::map<Edge, int> directed;
    for (int f : faces)
      for (int k = 0; k < 3; ++k) ++directed[{mesh.F(f, k), mesh.F(f, (k + 1) % 3)}];
    std::map<int, int> next;
    std::set<int> vertexSet;
    for (const auto& [e, count] : directed) {
      vertexSet.insert(e.first);
      if (!directed.count({e.second, e.first})) {
        PIXELCLOTH_CHECK(!next.count(e.first), garment.name << ": patch in layout " << garment.layouts[patch.layout]
                                                            << " touches itself at vertex " << e.first
                                                            << "; its boundary is not one simple loop");
        next[e.first] = e.second;
      }
    }
    patch.vertices.assign(vertexSet.begin(), vertexSet.end());
    PIXELCLOTH_CHECK(!next.empty(), garment.name << ": a patch has no boundary");
    int start = next.begin()->first, v = start;
    do {
      patch.boundary.push_back(v);
      v = next.at(v);
    } while (v != start && patch.boundary.size() <= next.size());
    PIXELCLOTH_CHECK(patch.boundary.size() == next.size(),
                     garment.name << ": a patch in layout " << garment.layouts[patch.layout] << " has " << next.size()
                                  << " boundary edges but its outer loop has " << patch.boundary.size()
                                  << "; a cut probably ends inside the patch");
    std::set<int> boundarySet(patch.boundary.begin(), patch.boundary.end());
    for (int u : patch.vertices)
      if (!boundarySet.count(u)) patch.interior.push_back(u);
    patches.push_back(std::move(patch));
  }
  // Stable order: layout, then rows top to bottom, then left to right. A row is the top of the patch's UV box in
  // steps of kRowStep: patches between the same two horizontal cage lines share their top exactly, and centroids
  // (which differ with the triangulation) would split such a row.
  constexpr double kRowStep = 0.05;
  std::vector<std::tuple<int, double, double, size_t>> order;
  for (size_t i = 0; i < patches.size(); ++i) {
    Eigen::AlignedBox2d box;
    for (int u : patches[i].vertices) box.extend(garment.uvOf(u, patches[i].layout));
    order.emplace_back(patches[i].layout, -std::round(box.max().y() / kRowStep), box.center().x(), i);
  }
  std::sort(order.begin(), order.end());
  std::vector<Patch> sorted;
  for (const auto& item : order) {
    sorted.push_back(patches[std::get<3>(item)]);
    sorted.back().id = static_cast<int>(sorted.size()) - 1;
  }
  return sorted;
}

PatchMesh patchMesh(const garment::Garment& garment, const Patch& patch) {
  PatchMesh out;
  std::map<int, int> local;
  for (int v : patch.vertices) {
    local[v] = static_cast<int>(out.globalVertex.size());
    out.globalVertex.push_back(v);
  }
  out.uv.resize(patch.vertices.size(), 2);
  for (size_t i = 0; i < patch.vertices.size(); ++i) out.uv.row(i) = garment.uvOf(patch.vertices[i], patch.layout);
  out.F.resize(patch.faces.size(), 3);
  for (size_t i = 0; i < patch.faces.size(); ++i)
    for (int k = 0; k < 3; ++k) out.F(i, k) = local.at(garment.mesh.F(patch.faces[i], k));
  for (int v : patch.boundary) out.boundary.push_back(local.at(v));
  for (int v : patch.interior) out.interior.push_back(local.at(v));
  return out;
}

Eigen::Vector2d patchPixelExtent(const garment::Garment& garment, const Patch& patch, int size) {
  const ImageFrame frame = layoutFrame(garment, patch.layout, size);
  Eigen::AlignedBox2d box;
  for (int v : patch.vertices) {
    const int row = garment.vertexUV(v, patch.layout);
    PIXELCLOTH_CHECK(row >= 0, garment.name << ": patch " << patch.id << " uses vertex " << v + 1 << ", which layout "
                                            << garment.layouts[patch.layout] << " lacks");
    box.extend(Eigen::Vector2d(garment.mesh.UV.row(row).transpose()));
  }
  return box.sizes() / frame.metresPerPixel;
}

}  // namespace pixelcloth::patches
