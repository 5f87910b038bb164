// Shared part of the garment templates: the flat-pattern mesher (CGAL), seam matching across layouts, merging into one
// mesh, and queries on Garment.
#include "pixelcloth/garment/garment.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#include "garment_pattern.h"
#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::garment {

namespace {
const core::EnumNames<CurveKind, 5> kCurveKinds{"curve kind",
                                                {{{CurveKind::Seam, "seam"},
                                                  {CurveKind::Loop, "loop"},
                                                  {CurveKind::CentreLine, "centre_line"},
                                                  {CurveKind::Opening, "opening"},
                                                  {CurveKind::Split, "split"}}}};
}  // namespace

const char* curveKindName(CurveKind kind) { return kCurveKinds.name(kind); }

CurveKind curveKindFromName(const std::string& name, const std::string& context) {
  return kCurveKinds.fromName(name, context);
}

using namespace core;

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using MeshVertexBase = CGAL::Delaunay_mesh_vertex_base_2<Kernel>;
using MeshFaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<MeshVertexBase, MeshFaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds>;
using SizeCriteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using VertexHandle = Cdt::Vertex_handle;

/// Shape bound B of the mesher: sin^2 of the smallest angle, 0.125 <=> 20.7 degrees (the largest bound for which
/// Ruppert's refinement is guaranteed to terminate).
constexpr double kShapeBound = 0.125;
/// Two arc-length fractions closer than this are the same seam point.
constexpr double kParamTolerance = 1e-9;
constexpr int kMaxStitchRounds = 20;
constexpr int kMaxSizeTrials = 8;
/// Relative tolerance on the vertex count: stop searching the edge-length bound once within it.
constexpr double kVertexCountTolerance = 0.02;

/// The triangulation of one layout, before merging.
struct LayoutMesh {
  Eigen::MatrixX2d UV;                      // #v x 2 layout coordinates
  Eigen::MatrixX3i F;                       // counter-clockwise in UV
  std::vector<std::vector<int>> chains;     // per curve: vertices from t = 0 to t = 1 (empty if not in the layout)
  std::vector<std::vector<double>> params;  // per curve: arc-length fractions of those vertices
};

Eigen::Vector2d toEigen(const Kernel::Point_2& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

/// Triangulates one layout with the curves sampled at `samples[curve]` as constraints, refined to the size bound,
/// and reads back each curve's vertex chain (the mesher may have split constrained edges).
LayoutMesh meshLayout(const std::vector<pattern::Curve>& curves, const pattern::Layout& layout,
                      const std::vector<std::vector<double>>& samples, double maxEdge) {
  Cdt cdt;
  const double sign = layout.mirrored ? -1.0 : 1.0;
  std::vector<std::vector<VertexHandle>> handles(curves.size());
  for (int c : layout.curves) {
    for (double t : samples[c]) {
      Eigen::Vector2d xy = curves[c].at(t);
      handles[c].push_back(cdt.insert(Kernel::Point_2(sign * xy.x(), xy.y())));
    }
    for (size_t i = 0; i + 1 < handles[c].size(); ++i) cdt.insert_constraint(handles[c][i], handles[c][i + 1]);
  }
  CGAL::refine_Delaunay_mesh_2(cdt, SizeCriteria(kShapeBound, maxEdge));

  LayoutMesh mesh;
  std::map<VertexHandle, int> index;
  std::vector<Eigen::Vector2d> points;
  std::vector<Eigen::Vector3i> faces;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    Eigen::Vector3i face;
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = index.emplace(f->vertex(k), static_cast<int>(points.size()));
      if (inserted) points.push_back(toEigen(f->vertex(k)->point()));
      face[k] = it->second;
    }
    faces.push_back(face);
  }
  mesh.UV.resize(static_cast<int>(points.size()), 2);
  for (size_t i = 0; i < points.size(); ++i) mesh.UV.row(i) = points[i].transpose();
  mesh.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) mesh.F.row(i) = faces[i].transpose();

  // Walk each curve's constrained sub-edges from sample to sample: they are collinear with the sample segment.
  mesh.chains.resize(curves.size());
  mesh.params.resize(curves.size());
  for (int c : layout.curves) {
    auto& chain = mesh.chains[c];
    auto& params = mesh.params[c];
    auto indexOf = [&](VertexHandle v) {
      auto it = index.find(v);
      if (it == index.end()) throw std::logic_error("garment mesher: curve '" + curves[c].name + "' left the domain");
      return it->second;
    };
    chain.push_back(indexOf(handles[c][0]));
    params.push_back(samples[c][0]);
    for (size_t i = 0; i + 1 < handles[c].size(); ++i) {
      VertexHandle from = handles[c][i], to = handles[c][i + 1];
      Eigen::Vector2d a = toEigen(from->point()), b = toEigen(to->point());
      double segmentLength = (b - a).norm();
      Eigen::Vector2d direction = (b - a) / segmentLength;
      VertexHandle current = from;
      for (int steps = 0; current != to; ++steps) {
        if (steps > 100000) throw std::logic_error("garment mesher: lost along curve '" + curves[c].name + "'");
        VertexHandle next;
        double best = -2;
        Cdt::Edge_circulator edge = cdt.incident_edges(current), done = edge;
        do {
          if (cdt.is_infinite(*edge) || !cdt.is_constrained(*edge)) continue;
          VertexHandle p = edge->first->vertex(Cdt::cw(edge->second));
          VertexHandle q = edge->first->vertex(Cdt::ccw(edge->second));
          VertexHandle other = p == current ? q : p;
          double score = (toEigen(other->point()) - toEigen(current->point())).normalized().dot(direction);
          if (score > best) best = score, next = other;
        } while (++edge != done);
        if (best < 1 - 1e-6) {
          throw std::logic_error("garment mesher: no constrained edge continues curve '" + curves[c].name + "'");
        }
        current = next;
        chain.push_back(indexOf(current));
        // A sample keeps its fraction exactly (a joint must come back as the same point in the next round).
        double fraction = (toEigen(current->point()) - a).norm() / segmentLength;
        params.push_back(current == to ? samples[c][i + 1]
                                       : samples[c][i] + (samples[c][i + 1] - samples[c][i]) * fraction);
      }
    }
  }
  return mesh;
}

/// Sorted union of two sorted parameter lists, points closer than kParamTolerance merged.
std::vector<double> unionParams(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> all(a);
  all.insert(all.end(), b.begin(), b.end());
  std::sort(all.begin(), all.end());
  std::vector<double> result;
  for (double t : all) {
    if (result.empty() || t - result.back() > kParamTolerance) result.push_back(t);
  }
  result.front() = 0.0;
  result.back() = 1.0;
  return result;
}

/// Meshes all layouts at one size bound until every stitched curve has the same samples in every layout: after each
/// round the samples of a stitched curve become the union of what all layouts ended with (the mesher splits
/// encroached constrained edges differently in each layout), and all layouts are meshed again.
std::vector<LayoutMesh> meshStitched(const std::vector<pattern::Curve>& curves,
                                     const std::vector<pattern::Layout>& layouts, double maxEdge, double spacing,
                                     int& rounds) {
  std::vector<std::vector<std::vector<double>>> samples(layouts.size(),
                                                        std::vector<std::vector<double>>(curves.size()));
  for (size_t l = 0; l < layouts.size(); ++l) {
    for (int c : layouts[l].curves) {
      // Evenly spaced between consecutive joints, the joints' fractions themselves exactly.
      std::vector<double> breaks = {0.0};
      for (int j : curves[c].joints) breaks.push_back(curves[c].paramOf(j));
      breaks.push_back(1.0);
      std::sort(breaks.begin(), breaks.end());
      samples[l][c].push_back(0.0);
      for (size_t b = 0; b + 1 < breaks.size(); ++b) {
        const double from = breaks[b], to = breaks[b + 1];
        int n = std::max(1, static_cast<int>(std::ceil((to - from) * curves[c].length() / spacing - 1e-9)));
        for (int k = 1; k <= n; ++k) samples[l][c].push_back(k == n ? to : from + (to - from) * k / n);
      }
    }
  }
  for (rounds = 1; rounds <= kMaxStitchRounds; ++rounds) {
    std::vector<LayoutMesh> meshes;
    for (size_t l = 0; l < layouts.size(); ++l) meshes.push_back(meshLayout(curves, layouts[l], samples[l], maxEdge));
    bool agree = true;
    for (size_t c = 0; c < curves.size(); ++c) {
      if (!curves[c].stitched) {
        for (size_t l = 0; l < layouts.size(); ++l) samples[l][c] = meshes[l].params[c];
        continue;
      }
      std::vector<double> merged;
      for (size_t l = 0; l < layouts.size(); ++l)
        merged = merged.empty() ? meshes[l].params[c] : unionParams(merged, meshes[l].params[c]);
      for (size_t l = 0; l < layouts.size(); ++l) {
        if (meshes[l].params[c].size() != merged.size()) agree = false;
        samples[l][c] = merged;
      }
    }
    if (agree) return meshes;
  }
  throw std::logic_error("garment mesher: stitched seams did not agree after " + std::to_string(kMaxStitchRounds) +
                         " rounds");
}

/// One mesh from the layouts: a vertex on a stitched curve becomes one vertex with one UV per layout.
pattern::MergedPattern merge(const std::vector<pattern::Curve>& curves, const std::vector<pattern::Layout>& layouts,
                             const std::vector<LayoutMesh>& meshes) {
  const int numLayouts = static_cast<int>(layouts.size());
  std::vector<std::vector<int>> global(numLayouts);
  std::vector<Eigen::Vector2d> xy;
  for (int l = 0; l < numLayouts; ++l) {
    global[l].assign(meshes[l].UV.rows(), -1);
    for (size_t c = 0; c < curves.size(); ++c) {
      if (!curves[c].stitched || meshes[l].chains[c].empty()) continue;
      int reference = 0;
      while (meshes[reference].chains[c].empty()) ++reference;
      if (reference == l) continue;
      const auto& mine = meshes[l].chains[c];
      const auto& theirs = meshes[reference].chains[c];
      if (mine.size() != theirs.size()) throw std::logic_error("garment mesher: seam '" + curves[c].name + "' differs");
      for (size_t k = 0; k < mine.size(); ++k) {
        int g = global[reference][theirs[k]];
        if (global[l][mine[k]] != -1 && global[l][mine[k]] != g) {
          throw std::logic_error("garment mesher: seam '" + curves[c].name + "' joins two different vertices");
        }
        global[l][mine[k]] = g;
      }
    }
    const double sign = layouts[l].mirrored ? -1.0 : 1.0;
    for (int v = 0; v < meshes[l].UV.rows(); ++v) {
      if (global[l][v] != -1) continue;
      global[l][v] = static_cast<int>(xy.size());
      xy.emplace_back(sign * meshes[l].UV(v, 0), meshes[l].UV(v, 1));
    }
  }
  pattern::MergedPattern merged;
  const int numVertices = static_cast<int>(xy.size());
  merged.XY.resize(numVertices, 2);
  for (int v = 0; v < numVertices; ++v) merged.XY.row(v) = xy[v].transpose();
  int numUV = 0, numFaces = 0;
  for (const auto& mesh : meshes)
    numUV += static_cast<int>(mesh.UV.rows()), numFaces += static_cast<int>(mesh.F.rows());
  merged.UV.resize(numUV, 2);
  merged.F.resize(numFaces, 3);
  merged.FUV.resize(numFaces, 3);
  merged.faceLayout.resize(numFaces);
  merged.vertexUV = Eigen::MatrixXi::Constant(numVertices, numLayouts, -1);
  merged.chains.assign(numLayouts, std::vector<std::vector<int>>(curves.size()));
  int uvOffset = 0, faceOffset = 0;
  for (int l = 0; l < numLayouts; ++l) {
    const LayoutMesh& mesh = meshes[l];
    merged.UV.middleRows(uvOffset, mesh.UV.rows()) = mesh.UV;
    for (int v = 0; v < mesh.UV.rows(); ++v) merged.vertexUV(global[l][v], l) = uvOffset + v;
    for (int f = 0; f < mesh.F.rows(); ++f) {
      for (int k = 0; k < 3; ++k) {
        merged.F(faceOffset + f, k) = global[l][mesh.F(f, k)];
        merged.FUV(faceOffset + f, k) = uvOffset + mesh.F(f, k);
      }
      merged.faceLayout[faceOffset + f] = l;
    }
    for (size_t c = 0; c < curves.size(); ++c) {
      for (int v : mesh.chains[c]) merged.chains[l][c].push_back(global[l][v]);
    }
    uvOffset += static_cast<int>(mesh.UV.rows());
    faceOffset += static_cast<int>(mesh.F.rows());
  }
  return merged;
}

}  // namespace

namespace pattern {

double Curve::length() const {
  double total = 0;
  for (size_t i = 0; i + 1 < points.size(); ++i) total += (points[i + 1] - points[i]).norm();
  return total;
}

double Curve::paramOf(int index) const {
  double walked = 0;
  for (int i = 0; i < index; ++i) walked += (points[i + 1] - points[i]).norm();
  return index + 1 == static_cast<int>(points.size()) ? 1.0 : walked / length();
}

Eigen::Vector2d Curve::at(double t) const {
  if (t <= 0) return points.front();
  if (t >= 1) return points.back();
  // Fractions computed exactly as paramOf does, so that a joint's fraction gives back the joint bit for bit.
  const double total = length();
  double walked = 0;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const double f0 = walked / total;
    walked += (points[i + 1] - points[i]).norm();
    const double f1 = i + 2 == points.size() ? 1.0 : walked / total;
    if (t == f0) return points[i];
    if (t == f1) return points[i + 1];
    if (t < f1 && f1 > f0) return points[i] + (t - f0) / (f1 - f0) * (points[i + 1] - points[i]);
  }
  return points.back();
}

Curve straightCurve(const std::string& name, const Eigen::Vector2d& a, const Eigen::Vector2d& b, bool stitched) {
  return Curve{name, {a, b}, stitched};
}

Curve polylineCurve(const std::string& name, const std::vector<Eigen::Vector2d>& points, bool stitched) {
  Curve curve{name, points, stitched};
  for (int i = 1; i + 1 < static_cast<int>(points.size()); ++i) curve.joints.push_back(i);
  return curve;
}

MergedPattern meshPattern(const std::vector<Curve>& curves, const std::vector<Layout>& layouts, int targetVertices,
                          double area, double boundarySpacing) {
  // Vertex count ~ 2 area / bound^2 for the meshes Ruppert's refinement produces; refined by trials assuming
  // count ~ 1 / bound^2, and by bisection (in log scale) once the target is bracketed: the count is only roughly
  // monotone in the bound.
  double maxEdge = std::sqrt(2.0 * area / targetVertices);
  double tooFine = 0, tooCoarse = 0;  // bounds known to give too many / too few vertices (0: none yet)
  MergedPattern best;
  int bestMiss = -1, trials = 0;
  while (trials < kMaxSizeTrials) {
    ++trials;
    int rounds = 0;
    std::vector<LayoutMesh> meshes = meshStitched(curves, layouts, maxEdge, boundarySpacing * maxEdge, rounds);
    MergedPattern merged = merge(curves, layouts, meshes);
    merged.stats.stitchRounds = rounds;
    merged.stats.maxEdgeLength = maxEdge;
    const int count = static_cast<int>(merged.XY.rows());
    const int miss = std::abs(count - targetVertices);
    if (bestMiss < 0 || miss < bestMiss) best = std::move(merged), bestMiss = miss;
    if (miss <= kVertexCountTolerance * targetVertices) break;
    (count > targetVertices ? tooFine : tooCoarse) = maxEdge;
    maxEdge = tooFine > 0 && tooCoarse > 0 ? std::sqrt(tooFine * tooCoarse)
                                           : maxEdge * std::sqrt(static_cast<double>(count) / targetVertices);
  }
  best.stats.sizeTrials = trials;
  best.stats.minAngleDegrees = minAngleDegrees(best.UV, best.FUV);
  return best;
}

std::vector<std::vector<int>> boundaryLoops(int numVertices, const Eigen::MatrixX3i& F) {
  std::unordered_set<std::uint64_t> directed;
  auto key = [](int a, int b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b); };
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) directed.insert(key(F(f, k), F(f, (k + 1) % 3)));
  std::vector<int> next(numVertices, -1);
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      int a = F(f, k), b = F(f, (k + 1) % 3);
      if (directed.count(key(b, a))) continue;
      if (next[a] != -1) throw std::logic_error("boundaryLoops: vertex " + std::to_string(a) + " is on two boundaries");
      next[a] = b;
    }
  }
  std::vector<std::vector<int>> loops;
  std::vector<bool> seen(numVertices, false);
  for (int start = 0; start < numVertices; ++start) {
    if (next[start] == -1 || seen[start]) continue;
    std::vector<int> loop;
    for (int v = start; !seen[v]; v = next[v]) {
      if (next[v] == -1) throw std::logic_error("boundaryLoops: boundary ends at vertex " + std::to_string(v));
      seen[v] = true;
      loop.push_back(v);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

double minAngleDegrees(const Eigen::MatrixX2d& UV, const Eigen::MatrixX3i& FUV) {
  double smallest = 180;
  for (int f = 0; f < FUV.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector2d p = UV.row(FUV(f, k)), a = UV.row(FUV(f, (k + 1) % 3)), b = UV.row(FUV(f, (k + 2) % 3));
      Eigen::Vector2d u = a - p, w = b - p;
      double angle = std::atan2(std::abs(u.x() * w.y() - u.y() * w.x()), u.dot(w));
      smallest = std::min(smallest, angle * 180.0 / M_PI);
    }
  }
  return smallest;
}

}  // namespace pattern

std::string PatternMeshingStats::summary(int numVertices) const {
  std::ostringstream out;
  out << std::fixed << numVertices << " vertices, min angle " << std::setprecision(1) << minAngleDegrees << " deg, "
      << stitchRounds << " stitch rounds, " << sizeTrials << " size trials, " << std::setprecision(3) << seconds
      << " s";
  return out.str();
}

int Garment::layoutIndex(const std::string& layoutName) const {
  for (size_t l = 0; l < layouts.size(); ++l)
    if (layouts[l] == layoutName) return static_cast<int>(l);
  std::string known;
  for (const auto& l : layouts) known += (known.empty() ? "" : ", ") + l;
  PIXELCLOTH_FAIL(name << ": no layout '" << layoutName << "'; this garment has: " << known);
}

Eigen::AlignedBox2d Garment::layoutBounds(int layout) const {
  PIXELCLOTH_CHECK(layout >= 0 && layout < numLayouts(),
                   name << ": layout " << layout << " requested, but the garment has " << numLayouts());
  Eigen::AlignedBox2d box;
  for (int f = 0; f < mesh.FUV.rows(); ++f) {
    if (faceLayout[f] != layout) continue;
    for (int k = 0; k < 3; ++k) box.extend(Eigen::Vector2d(mesh.UV.row(mesh.FUV(f, k))));
  }
  return box;
}

double Garment::length() const { return layoutBounds(0).sizes().y(); }

const Seam* Garment::findSeam(const std::string& seamName) const {
  for (const auto& seam : seams)
    if (seam.name == seamName) return &seam;
  return nullptr;
}

const CageLine* Garment::findLine(const std::string& lineName) const {
  for (const auto& line : lines)
    if (line.name == lineName) return &line;
  return nullptr;
}

std::string Garment::summary() const {
  std::ostringstream out;
  out << name << ": " << mesh.numVertices() << " vertices, " << mesh.numFaces() << " faces, layouts ";
  for (size_t l = 0; l < layouts.size(); ++l) out << (l ? "+" : "") << layouts[l];
  out << ", " << panels.size() << " panels, " << seams.size() << " seams, " << openings.size() << " openings, "
      << lines.size() << " cage lines";
  return out.str();
}

}  // namespace pixelcloth::garment
