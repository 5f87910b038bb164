// Splitting a garment's triangles along added lines (see pattern_lines.h).
#include "pixelcloth/garment/pattern_lines.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "pixelcloth/core/edge_key.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::garment {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Puts `n` between every consecutive a, b (either order) of `chain`; `closed` chains also between last and first.
void insertIntoChain(std::vector<int>& chain, bool closed, int a, int b, int n) {
  const size_t count = chain.size();
  for (size_t i = 0; i + 1 < count + (closed ? 1 : 0); ++i) {
    const int x = chain[i], y = chain[(i + 1) % count];
    if ((x == a && y == b) || (x == b && y == a)) {
      chain.insert(chain.begin() + static_cast<long>(i) + 1, n);
      return;  // a simple chain runs along an edge at most once
    }
  }
}

Eigen::Vector2d uvOf(const Garment& garment, int v, int layout) { return garment.mesh.UV.row(garment.vertexUV(v, layout)); }

/// Every mesh edge a seam, opening or cage line runs along, by core::edgeKey.
std::unordered_set<std::uint64_t> curveEdgeKeys(const Garment& garment) {
  std::unordered_set<std::uint64_t> edges;
  auto add = [&](const std::vector<int>& vertices, bool closed) {
    for (size_t k = 0; k + 1 < vertices.size() + (closed ? 1 : 0); ++k)
      edges.insert(core::edgeKey(vertices[k], vertices[(k + 1) % vertices.size()]));
  };
  for (const Seam& seam : garment.seams) add(seam.vertices, false);
  for (const Opening& opening : garment.openings) add(opening.vertices, true);
  for (const CageLine& line : garment.lines) add(line.vertices, line.closed);
  return edges;
}

/// The angle at p of triangle (p, q, r), radians.
double angleAt(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  return std::atan2(std::abs(cross2(q - p, r - p)), (q - p).dot(r - p));
}

/// The smallest angle of face f in pattern space, radians.
double smallestAngle(const core::Mesh& mesh, int f) {
  double smallest = M_PI;
  for (int k = 0; k < 3; ++k)
    smallest = std::min(smallest, angleAt(mesh.UV.row(mesh.FUV(f, k)), mesh.UV.row(mesh.FUV(f, (k + 1) % 3)),
                                          mesh.UV.row(mesh.FUV(f, (k + 2) % 3))));
  return smallest;
}

}  // namespace

int splitEdge(Garment& garment, int a, int b, double t) {
  core::Mesh& mesh = garment.mesh;
  PIXELCLOTH_CHECK(std::isfinite(t) && t > 0 && t < 1,
                   garment.name << ": splitting edge (" << a << ", " << b << ") at " << t << ", expected 0 < t < 1");
  std::vector<int> faces;
  for (int f = 0; f < mesh.numFaces(); ++f) {
    int hits = 0;
    for (int k = 0; k < 3; ++k) hits += mesh.F(f, k) == a || mesh.F(f, k) == b;
    if (hits == 2) faces.push_back(f);
  }
  PIXELCLOTH_CHECK(!faces.empty(), garment.name << ": (" << a << ", " << b << ") is no edge of the mesh");

  const int n = mesh.numVertices();
  mesh.V.conservativeResize(n + 1, Eigen::NoChange);
  mesh.V.row(n) = (1 - t) * mesh.V.row(a) + t * mesh.V.row(b);
  garment.vertexUV.conservativeResize(n + 1, Eigen::NoChange);
  garment.vertexUV.row(n).setConstant(-1);
  for (int f : faces) {
    const int layout = garment.faceLayout[f];
    if (garment.vertexUV(n, layout) >= 0) continue;
    const int row = static_cast<int>(mesh.UV.rows());
    mesh.UV.conservativeResize(row + 1, Eigen::NoChange);
    mesh.UV.row(row) = (1 - t) * uvOf(garment, a, layout) + t * uvOf(garment, b, layout);
    garment.vertexUV(n, layout) = row;
  }

  // Face (x0, x1, x2) with the edge at corners (i, i + 1) becomes (x_i, n, x_i+2) and (n, x_i+1, x_i+2).
  const int numFaces = mesh.numFaces();
  const int added = static_cast<int>(faces.size());
  mesh.F.conservativeResize(numFaces + added, Eigen::NoChange);
  mesh.FUV.conservativeResize(numFaces + added, Eigen::NoChange);
  garment.faceLayout.conservativeResize(numFaces + added);
  garment.facePanel.conservativeResize(numFaces + added);
  for (int k = 0; k < added; ++k) {
    const int f = faces[k], g = numFaces + k;
    int i = 0;
    while (!((mesh.F(f, i) == a && mesh.F(f, (i + 1) % 3) == b) || (mesh.F(f, i) == b && mesh.F(f, (i + 1) % 3) == a)))
      ++i;
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    const int uvN = garment.vertexUV(n, garment.faceLayout[f]);
    const Eigen::RowVector3i corners = mesh.F.row(f), uvs = mesh.FUV.row(f);
    mesh.F.row(f) << corners[i], n, corners[i2];
    mesh.FUV.row(f) << uvs[i], uvN, uvs[i2];
    mesh.F.row(g) << n, corners[i1], corners[i2];
    mesh.FUV.row(g) << uvN, uvs[i1], uvs[i2];
    garment.faceLayout[g] = garment.faceLayout[f];
    garment.facePanel[g] = garment.facePanel[f];
  }
  for (auto& [name, values] : mesh.vertexAttributes) {
    values.conservativeResize(n + 1, Eigen::NoChange);
    values.row(n) = (1 - t) * values.row(a) + t * values.row(b);
  }
  for (auto& [name, values] : mesh.faceAttributes) {
    values.conservativeResize(numFaces + added);
    for (int k = 0; k < added; ++k) values[numFaces + k] = values[faces[k]];
  }

  for (Seam& seam : garment.seams) insertIntoChain(seam.vertices, false, a, b, n);
  for (Opening& opening : garment.openings) insertIntoChain(opening.vertices, true, a, b, n);
  for (CageLine& line : garment.lines) insertIntoChain(line.vertices, line.closed, a, b, n);
  garment.recipe = nullptr;
  return n;
}

std::vector<int> insertPatternLine(Garment& garment, int layout, int from, int to, double snap) {
  const int numVertices = garment.mesh.numVertices();
  PIXELCLOTH_CHECK(layout >= 0 && layout < garment.numLayouts(),
                   garment.name << ": layout " << layout << " does not exist");
  for (int v : {from, to})
    PIXELCLOTH_CHECK(v >= 0 && v < numVertices && garment.vertexUV(v, layout) >= 0,
                     garment.name << ": vertex " << v << " is not in layout " << garment.layouts[layout]);
  PIXELCLOTH_CHECK(snap >= 0 && snap < 0.5, garment.name << ": snap " << snap << ", expected 0 to 0.5");
  const Eigen::Vector2d target = uvOf(garment, to, layout);
  // The layout's outline vertices (on an edge that only one of its faces has): the line never turns onto one of them
  // on its way, which would run it along the outline, or through a vertex another line across the seam takes too.
  std::map<std::pair<int, int>, int> edgeUses;
  for (int f = 0; f < garment.mesh.numFaces(); ++f)
    if (garment.faceLayout[f] == layout)
      for (int k = 0; k < 3; ++k) {
        const int a = garment.mesh.F(f, k), b = garment.mesh.F(f, (k + 1) % 3);
        ++edgeUses[{std::min(a, b), std::max(a, b)}];
      }
  std::set<int> outline;
  for (const auto& [edge, uses] : edgeUses)
    if (uses == 1) outline.insert({edge.first, edge.second});
  // Nor does it take a step along an edge of a seam, opening or cage line: it crosses other curves, never runs on them.
  std::unordered_set<std::uint64_t> curveEdges = curveEdgeKeys(garment);
  auto key = [](int a, int b) { return core::edgeKey(a, b); };

  std::vector<int> chain = {from};
  int current = from;
  // Every step reaches a vertex nearer the target along the segment; a bound guards against a loop all the same.
  for (int step = 0; current != to; ++step) {
    PIXELCLOTH_CHECK(step <= garment.mesh.numVertices(),
                     garment.name << ": the line from vertex " << from << " to " << to << " in layout "
                                  << garment.layouts[layout] << " does not reach its end");
    const core::Mesh& mesh = garment.mesh;
    const Eigen::Vector2d p = uvOf(garment, current, layout);
    const Eigen::Vector2d d = target - p;
    // Among the layout's faces around `current`, the one whose wedge holds the direction to the target.
    int bestA = -1, bestB = -1;
    double best = -std::numeric_limits<double>::infinity();
    bool reached = false;
    for (int f = 0; f < mesh.numFaces() && !reached; ++f) {
      if (garment.faceLayout[f] != layout) continue;
      for (int k = 0; k < 3; ++k) {
        if (mesh.F(f, k) != current) continue;
        const int a = mesh.F(f, (k + 1) % 3), b = mesh.F(f, (k + 2) % 3);  // counter-clockwise after `current`
        if (a == to || b == to) {
          reached = true;
          break;
        }
        const Eigen::Vector2d ea = uvOf(garment, a, layout) - p, eb = uvOf(garment, b, layout) - p;
        const double score = std::min(cross2(ea, d) / (ea.norm() * d.norm()), cross2(d, eb) / (eb.norm() * d.norm()));
        if (score > best) best = score, bestA = a, bestB = b;
      }
    }
    if (reached) {
      chain.push_back(to);
      break;
    }
    PIXELCLOTH_CHECK(bestA >= 0 && best > -1e-9,
                     garment.name << ": the straight pattern line from vertex " << from << " to vertex " << to
                                  << " leaves layout " << garment.layouts[layout] << " at vertex " << current
                                  << " (the layout's outline is concave there)");
    const Eigen::Vector2d a = uvOf(garment, bestA, layout), e = uvOf(garment, bestB, layout) - a;
    const double denominator = cross2(e, d);
    const double t = denominator == 0 ? 0.0 : std::clamp(cross2(p - a, d) / denominator, 0.0, 1.0);
    // An end of the crossed edge within `snap` of its length from the line is taken instead of a split: by distance
    // from the line, not along the edge, so that a line nearly parallel to an edge takes its end rather than cutting
    // two slivers off it.
    const Eigen::Vector2d unit = d.normalized();
    const double fromA = std::abs(cross2(a - p, unit)), fromB = std::abs(cross2(a + e - p, unit));
    // (nor onto a vertex whose last step to `to` would run along a curve)
    auto takes = [&](int w, double distance) {
      return distance <= snap * e.norm() && !outline.count(w) && !curveEdges.count(key(current, w)) &&
             !curveEdges.count(key(w, to));
    };
    const bool takeA = takes(bestA, fromA), takeB = takes(bestB, fromB);
    int next;
    if (takeA && (!takeB || fromA <= fromB)) {
      next = bestA;
    } else if (takeB) {
      next = bestB;
    } else {
      next = splitEdge(garment, bestA, bestB, t);
      if (curveEdges.erase(key(bestA, bestB))) curveEdges.insert({key(bestA, next), key(next, bestB)});
    }
    PIXELCLOTH_CHECK(std::find(chain.begin(), chain.end(), next) == chain.end(),
                     garment.name << ": the line from vertex " << from << " to " << to << " in layout "
                                  << garment.layouts[layout] << " comes back to vertex " << next);
    chain.push_back(next);
    current = next;
  }
  return chain;
}

int flipThinTriangles(Garment& garment, double belowDegrees) {
  core::Mesh& mesh = garment.mesh;
  auto key = [](int a, int b) { return core::edgeKey(a, b); };
  const std::unordered_set<std::uint64_t> curveEdges = curveEdgeKeys(garment);
  const double thin = belowDegrees * M_PI / 180;
  int flips = 0;
  // Each pass visits every edge once; Lawson's flips end, and a few passes reach it.
  for (int pass = 0; pass < 20; ++pass) {
    std::unordered_map<std::uint64_t, std::vector<std::pair<int, int>>> edgeFaces;  // edge -> (face, corner of a)
    for (int f = 0; f < mesh.numFaces(); ++f)
      for (int k = 0; k < 3; ++k) edgeFaces[key(mesh.F(f, k), mesh.F(f, (k + 1) % 3))].push_back({f, k});
    std::vector<bool> touched(mesh.numFaces(), false);
    int passFlips = 0;
    for (const auto& [edge, faces] : edgeFaces) {
      if (faces.size() != 2 || curveEdges.count(edge)) continue;
      const auto [f, i] = faces[0];
      const auto [g, j] = faces[1];
      if (garment.faceLayout[f] != garment.faceLayout[g] || touched[f] || touched[g]) continue;
      if (std::min(smallestAngle(mesh, f), smallestAngle(mesh, g)) >= thin) continue;
      // f = (a, b, c) from corner i, g = (b, a, d) from corner j: the quad a, d, b, c runs counter-clockwise.
      const int a = mesh.F(f, i), b = mesh.F(f, (i + 1) % 3), c = mesh.F(f, (i + 2) % 3);
      const int d = mesh.F(g, (j + 2) % 3);
      if (mesh.F(g, j) != b || mesh.F(g, (j + 1) % 3) != a || edgeFaces.count(key(c, d))) continue;
      const int ua = mesh.FUV(f, i), ub = mesh.FUV(f, (i + 1) % 3), uc = mesh.FUV(f, (i + 2) % 3),
                ud = mesh.FUV(g, (j + 2) % 3);
      const Eigen::Vector2d pa = mesh.UV.row(ua), pb = mesh.UV.row(ub), pc = mesh.UV.row(uc), pd = mesh.UV.row(ud);
      if (angleAt(pc, pa, pb) + angleAt(pd, pb, pa) <= M_PI + 1e-9) continue;  // already Delaunay
      // The new triangles (a, d, c) and (d, b, c) must keep the layout's orientation (the quad is convex).
      if (cross2(pd - pa, pc - pa) <= 0 || cross2(pb - pd, pc - pd) <= 0) continue;
      mesh.F.row(f) << a, d, c;
      mesh.FUV.row(f) << ua, ud, uc;
      mesh.F.row(g) << d, b, c;
      mesh.FUV.row(g) << ud, ub, uc;
      touched[f] = touched[g] = true;
      ++passFlips;
    }
    flips += passFlips;
    if (passFlips == 0) break;
  }
  if (flips > 0) garment.recipe = nullptr;
  return flips;
}

double smallestPatternAngleDegrees(const Garment& garment) {
  double smallest = M_PI;
  for (int f = 0; f < garment.mesh.numFaces(); ++f) smallest = std::min(smallest, smallestAngle(garment.mesh, f));
  return smallest * 180 / M_PI;
}

}  // namespace pixelcloth::garment
