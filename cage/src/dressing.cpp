// Dressing a garment on a body (DESIGN.md "Dressing"; paper appendix): cage morph, Poisson carry, push-out,
// edge-length equalisation on the body, embedding.
#include "pixelcloth/cage/dressing.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "pixelcloth/core/edge_key.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/geometry.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/mesh_index.h"

namespace pixelcloth::cage {

namespace {

using core::edgeKey;

/// Closest-point queries on the rest body: the point and the smooth (vertex-normal blended) normal there.
class BodySurface {
 public:
  struct Hit {
    Eigen::Vector3d point, normal;
    core::MeshHit hit;  ///< for the next query near this one
  };

  explicit BodySurface(const body::Body& body) : index_(body.mesh.V, body.mesh.F) {
    normals_ = core::vertexNormals(body.mesh.V, body.mesh.F);
  }

  Hit closest(const Eigen::Vector3d& p) const { return hitOf(index_.closest(p)); }
  /// Same, starting the search from a previous hit nearby (much faster for small moves).
  Hit closest(const Eigen::Vector3d& p, const Hit& near) const { return hitOf(index_.closest(p, near.hit)); }
  /// The smooth normal at vertex v of the body.
  Eigen::Vector3d vertexNormal(int v) const { return normals_.row(v).transpose(); }

 private:
  Hit hitOf(const core::MeshHit& found) const {
    return {found.point, index_.smoothNormal(found.face, found.barycentric), found};
  }

  core::MeshIndex index_;
  Eigen::MatrixX3d normals_;
};

/// The garment's unique edges with their rest lengths in pattern space (per-corner UVs; a seam edge has one length
/// per layout, equal up to the mesher's tolerance: the first face's is kept).
struct PatternEdges {
  std::vector<std::pair<int, int>> edges;
  std::vector<double> restLength;
  std::unordered_map<std::uint64_t, int> index;  ///< edgeKey -> row of `edges`

  explicit PatternEdges(const garment::Garment& garment) {
    const auto& F = garment.mesh.F;
    const auto& FUV = garment.mesh.FUV;
    const auto& UV = garment.mesh.UV;
    for (int f = 0; f < F.rows(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const int j = (k + 1) % 3;
        const auto [it, added] = index.emplace(edgeKey(F(f, k), F(f, j)), static_cast<int>(edges.size()));
        if (!added) continue;
        edges.emplace_back(F(f, k), F(f, j));
        restLength.push_back((UV.row(FUV(f, k)) - UV.row(FUV(f, j))).norm());
      }
    }
  }
  /// Rest length of the edge (a, b), or -1 when the mesh has no such edge.
  double length(int a, int b) const {
    const auto it = index.find(edgeKey(a, b));
    return it == index.end() ? -1.0 : restLength[it->second];
  }
};

// ---------------------------------------------------------------------------------------------------------------------
// Cage morph

/// Where the morph puts the garment's cage vertices; a vertex on several matched curves (a junction) gets the mean.
struct CageTargets {
  std::map<int, Eigen::Vector3d> sum;
  std::map<int, int> count;
  void add(int v, const Eigen::Vector3d& p) {
    auto [it, added] = sum.emplace(v, p);
    if (!added) it->second += p;
    ++count[v];
  }
};

/// A polyline on the body: cumulative 3D arc length, for placing points at arc-length fractions.
struct BodyPolyline {
  std::vector<int> vertices;
  std::vector<double> arc;  ///< arc[i]: length from vertices[0] to vertices[i]
};

/// Point on the body polyline at arc length s (clamped), offset by `clearance` along the blended vertex normal.
Eigen::Vector3d pointAt(const body::Body& body, const BodySurface& surface, const BodyPolyline& line, double s,
                        double clearance) {
  const auto& V = body.mesh.V;
  const size_t n = line.vertices.size();
  size_t i = std::upper_bound(line.arc.begin(), line.arc.end(), s) - line.arc.begin();
  i = std::clamp<size_t>(i, 1, n - 1);
  const double span = line.arc[i] - line.arc[i - 1];
  const double t = span > 0 ? std::clamp((s - line.arc[i - 1]) / span, 0.0, 1.0) : 0.0;
  const int a = line.vertices[i - 1], b = line.vertices[i];
  const Eigen::Vector3d p = (1 - t) * V.row(a).transpose() + t * V.row(b).transpose();
  Eigen::Vector3d normal = (1 - t) * surface.vertexNormal(a) + t * surface.vertexNormal(b);
  if (normal.norm() < 1e-12) normal = surface.vertexNormal(a);
  return p + clearance * normal.normalized();
}

/// A junction shared by a garment curve and its body namesake: its index along each curve.
struct Anchor {
  int g = 0, b = 0;
};

/// The placement of one garment curve on one orientation of its body namesake (`body` already reversed if needed);
/// empty when the anchors are not in the same order along both curves.
std::vector<Eigen::Vector3d> placeCurve(const body::Body& body, const BodySurface& surface, const CageCurve& g,
                                        const std::vector<int>& bodyVertices, std::vector<Anchor> anchors,
                                        const PatternEdges& patternEdges, double clearance) {
  const int nG = static_cast<int>(g.vertices.size()), nB = static_cast<int>(bodyVertices.size());
  std::sort(anchors.begin(), anchors.end(), [](const Anchor& x, const Anchor& y) { return x.g < y.g; });
  if (!g.closed) {
    // Open curves also pair their ends, unless a junction already pins that end.
    if (anchors.empty() || anchors.front().g > 0) {
      if (!anchors.empty() && anchors.front().b <= 0) return {};
      anchors.insert(anchors.begin(), Anchor{0, 0});
    }
    if (anchors.back().g < nG - 1) {
      if (anchors.back().b >= nB - 1) return {};
      anchors.push_back(Anchor{nG - 1, nB - 1});
    }
    for (size_t k = 0; k + 1 < anchors.size(); ++k) {
      if (anchors[k + 1].b <= anchors[k].b) return {};
    }
  } else {
    // Body indices must increase cyclically: at most one wrap-around.
    int wraps = 0;
    for (size_t k = 0; k < anchors.size(); ++k) {
      if (anchors[(k + 1) % anchors.size()].b <= anchors[k].b) ++wraps;
    }
    if (wraps > 1) return {};
  }

  std::vector<Eigen::Vector3d> placed(nG);
  const size_t segments = g.closed ? anchors.size() : anchors.size() - 1;
  for (size_t k = 0; k < segments; ++k) {
    const Anchor from = anchors[k], to = anchors[(k + 1) % anchors.size()];
    // Steps along each curve from one anchor to the next (the whole loop when a closed curve has one anchor).
    int stepsG = to.g - from.g, stepsB = to.b - from.b;
    if (g.closed) {
      stepsG = ((stepsG % nG) + nG) % nG;
      stepsB = ((stepsB % nB) + nB) % nB;
      if (stepsG == 0) stepsG = nG;
      if (stepsB == 0) stepsB = nB;
    }
    BodyPolyline line;
    line.arc.push_back(0);
    for (int s = 0; s <= stepsB; ++s) {
      line.vertices.push_back(bodyVertices[(from.b + s) % nB]);
      if (s > 0) {
        line.arc.push_back(line.arc.back() +
                           (body.mesh.V.row(line.vertices[s]) - body.mesh.V.row(line.vertices[s - 1])).norm());
      }
    }
    std::vector<double> arcG(1, 0.0);
    for (int s = 1; s <= stepsG; ++s) {
      const double length = patternEdges.length(g.vertices[(from.g + s - 1) % nG], g.vertices[(from.g + s) % nG]);
      arcG.push_back(arcG.back() + std::max(length, 0.0));
    }
    for (int s = 0; s < stepsG; ++s) {
      const double fraction = arcG.back() > 0 ? arcG[s] / arcG.back() : 0.0;
      placed[(from.g + s) % nG] = pointAt(body, surface, line, fraction * line.arc.back(), clearance);
    }
    if (!g.closed && k + 1 == segments) {
      placed[to.g] = pointAt(body, surface, line, line.arc.back(), clearance);
    }
  }
  return placed;
}

/// Morphs every garment curve that has a body namesake onto it (design: split both at their shared junctions, place
/// by arc-length fraction, `clearance` outside along the body normal). Returns the targets of the cage vertices.
std::map<int, Eigen::Vector3d> morphCage(const body::Body& body, const BodySurface& surface, const Cage& bodyCage,
                                         const garment::Garment& garment, const Cage& garmentCage,
                                         const PatternEdges& patternEdges, double clearance) {
  std::unordered_map<int, std::string> garmentNodeAt;
  for (const CageNode& node : garmentCage.nodes) garmentNodeAt[node.vertex] = node.name;
  CageTargets targets;
  for (const CageCurve& g : garmentCage.curves) {
    const CageCurve* b = bodyCage.findCurve(g.name);
    if (b == nullptr) continue;
    PIXELCLOTH_CHECK(g.closed == b->closed, "dressing: garment cage curve '"
                                                << g.name << "' is " << (g.closed ? "closed" : "open")
                                                << " but its body namesake is " << (b->closed ? "closed" : "open"));
    std::unordered_map<int, int> bodyIndex;
    for (size_t j = 0; j < b->vertices.size(); ++j) bodyIndex[b->vertices[j]] = static_cast<int>(j);
    std::vector<Anchor> anchors;
    for (size_t i = 0; i < g.vertices.size(); ++i) {
      const auto named = garmentNodeAt.find(g.vertices[i]);
      if (named == garmentNodeAt.end()) continue;
      const int node = bodyCage.findNode(named->second);
      if (node < 0) continue;  // a garment-only junction (side panels): placed by arc length
      const auto onCurve = bodyIndex.find(bodyCage.nodes[node].vertex);
      PIXELCLOTH_CHECK(onCurve != bodyIndex.end(), "dressing: junction '" << named->second
                                                                          << "' lies on garment curve '" << g.name
                                                                          << "' but not on the body's");
      anchors.push_back(Anchor{static_cast<int>(i), onCurve->second});
    }
    PIXELCLOTH_CHECK(!g.closed || !anchors.empty(), "dressing: closed garment cage curve '"
                                                        << g.name << "' shares no junction with its body namesake");

    // Both orientations of the body curve; keep those whose junction order agrees, then the one nearer the garment's
    // rest placement (a loop through two junctions, like a bicep loop, fits both ways).
    std::vector<Eigen::Vector3d> best;
    double bestCost = std::numeric_limits<double>::infinity();
    for (bool reversed : {false, true}) {
      std::vector<int> bodyVertices = b->vertices;
      std::vector<Anchor> oriented = anchors;
      if (reversed) {
        std::reverse(bodyVertices.begin(), bodyVertices.end());
        for (Anchor& a : oriented) a.b = static_cast<int>(bodyVertices.size()) - 1 - a.b;
      }
      std::vector<Eigen::Vector3d> placed =
          placeCurve(body, surface, g, bodyVertices, oriented, patternEdges, clearance);
      if (placed.empty()) continue;
      double cost = 0;
      for (size_t i = 0; i < placed.size(); ++i)
        cost += (placed[i] - garment.mesh.V.row(g.vertices[i]).transpose()).squaredNorm();
      if (cost < bestCost) {
        bestCost = cost;
        best = std::move(placed);
      }
    }
    PIXELCLOTH_CHECK(!best.empty(), "dressing: the junctions of garment cage curve '"
                                        << g.name << "' come in a different order along its body namesake");
    for (size_t i = 0; i < best.size(); ++i) targets.add(g.vertices[i], best[i]);
  }
  std::map<int, Eigen::Vector3d> result;
  for (const auto& [v, p] : targets.sum) result[v] = p / targets.count[v];
  return result;
}

// ---------------------------------------------------------------------------------------------------------------------
// Poisson carry

/// Displacement of every vertex: `fixedDisplacement` on the cage vertices (Dirichlet), harmonic elsewhere. Weights:
/// cotangent weights of the rest 3D placement, clamped below at a small positive value (the pillow placement has a
/// few obtuse pairs whose cotangent sum is negative; clamping keeps the system an M-matrix, so the displacement obeys
/// the maximum principle and the solve stays positive definite).
Eigen::MatrixX3d harmonicDisplacement(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                      const std::map<int, Eigen::Vector3d>& fixedDisplacement) {
  const int n = static_cast<int>(V.rows());
  Eigen::MatrixX3d displacement = Eigen::MatrixX3d::Zero(n, 3);
  if (fixedDisplacement.empty()) return displacement;
  const Eigen::SparseMatrix<double> laplacian = core::cotangentLaplacian(V, F);
  std::vector<int> freeIndex(n, -1);
  int numFree = 0;
  for (int v = 0; v < n; ++v) {
    if (!fixedDisplacement.count(v)) freeIndex[v] = numFree++;
  }
  for (const auto& [v, d] : fixedDisplacement) displacement.row(v) = d.transpose();
  if (numFree == 0) return displacement;

  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(numFree, 3);
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(numFree);
  for (int column = 0; column < laplacian.outerSize(); ++column)
    for (Eigen::SparseMatrix<double>::InnerIterator it(laplacian, column); it; ++it) {
      const int i = static_cast<int>(it.row()), j = static_cast<int>(it.col());
      if (i >= j) continue;  // each edge once
      const double w = std::max(it.value(), 1e-3);
      for (const auto& [p, q] : {std::pair<int, int>{i, j}, std::pair<int, int>{j, i}}) {
        if (freeIndex[p] < 0) continue;
        diagonal[freeIndex[p]] += w;
        if (freeIndex[q] >= 0) {
          triplets.emplace_back(freeIndex[p], freeIndex[q], -w);
        } else {
          rhs.row(freeIndex[p]) += w * displacement.row(q);
        }
      }
    }
  // A tiny diagonal term keeps pieces without any cage vertex (none on the T-shirt) solvable: they do not move.
  const double regularisation = 1e-9 * std::max(diagonal.maxCoeff(), 1.0);
  for (int i = 0; i < numFree; ++i) triplets.emplace_back(i, i, diagonal[i] + regularisation);
  Eigen::SparseMatrix<double> L(numFree, numFree);
  L.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
  PIXELCLOTH_ASSERT(solver.info() == Eigen::Success, "dressing: the Poisson system could not be factorised");
  const Eigen::MatrixX3d solved = solver.solve(rhs);
  for (int v = 0; v < n; ++v) {
    if (freeIndex[v] >= 0) displacement.row(v) = solved.row(freeIndex[v]);
  }
  return displacement;
}

std::vector<double> log2Of(const Eigen::VectorXd& ratios) {
  std::vector<double> out;
  for (int i = 0; i < ratios.size(); ++i) out.push_back(std::log2(std::max(ratios[i], 1e-12)));
  return out;
}

/// The part a cloth vertex collides with (see Dressing::part).
std::vector<int> collisionPartOf(const body::Body& body, const garment::Garment& garment,
                                 const garment::Embedding& embedding) {
  const int numParts = static_cast<int>(body.parts.size());
  std::vector<std::vector<int>> partsOfFace(body.mesh.numFaces());
  for (int p = 0; p < numParts; ++p) {
    for (int f : body.parts[p].faces) {
      if (f >= 0 && f < body.mesh.numFaces()) partsOfFace[f].push_back(p);
    }
  }
  auto partNamed = [&](const std::string& name) {
    for (int p = 0; p < numParts; ++p) {
      if (body.parts[p].name == name) return p;
    }
    return -1;
  };
  const int torso = partNamed("torso"), leftArm = partNamed("left_arm"), rightArm = partNamed("right_arm");
  // The arm a vertex's sleeve panel belongs to, if any (panel names "left_sleeve_front", ...).
  std::vector<int> preferredArm(garment.mesh.numVertices(), -1);
  for (int f = 0; f < garment.mesh.numFaces(); ++f) {
    if (garment.facePanel.size() != garment.mesh.numFaces()) break;
    const int panel = garment.facePanel[f];
    if (panel < 0 || panel >= static_cast<int>(garment.panels.size())) continue;
    const std::string& name = garment.panels[panel];
    const int arm = name.rfind("left_sleeve", 0) == 0 ? leftArm : name.rfind("right_sleeve", 0) == 0 ? rightArm : -1;
    if (arm < 0) continue;
    for (int k = 0; k < 3; ++k) preferredArm[garment.mesh.F(f, k)] = arm;
  }
  std::vector<int> part(embedding.size(), torso >= 0 ? torso : 0);
  for (int v = 0; v < embedding.size(); ++v) {
    const std::vector<int>& candidates = partsOfFace[embedding.triangle[v]];
    if (candidates.empty()) continue;
    auto has = [&](int p) { return p >= 0 && std::find(candidates.begin(), candidates.end(), p) != candidates.end(); };
    part[v] = has(preferredArm[v]) ? preferredArm[v] : has(torso) ? torso : candidates.front();
  }
  return part;
}
}  // namespace

void DressingOptions::validate() const {
  PIXELCLOTH_CHECK(std::isfinite(clearance) && clearance >= 0 && clearance <= 0.05,
                   "dressing options: clearance must be in [0, 0.05] m, got " << clearance);
  PIXELCLOTH_CHECK(maxRelaxIterations >= 0 && maxRelaxIterations <= 100000,
                   "dressing options: maxRelaxIterations must be in [0, 100000], got " << maxRelaxIterations);
  PIXELCLOTH_CHECK(std::isfinite(relaxTolerance) && relaxTolerance > 0,
                   "dressing options: relaxTolerance must be positive, got " << relaxTolerance);
}

namespace {
double areaRatioQuantile(const Eigen::VectorXd& ratios, double q) {
  if (ratios.size() == 0) return 1.0;
  return core::quantile(std::vector<double>(ratios.data(), ratios.data() + ratios.size()), q);
}
}  // namespace

double Dressing::compressedAreaRatio() const { return areaRatioQuantile(areaRatioAfter, 0.05); }
double Dressing::stretchedAreaRatio() const { return areaRatioQuantile(areaRatioAfter, 0.95); }

double suggestedGrade(const Dressing& dressing) {
  const double compressed = dressing.compressedAreaRatio(), stretched = dressing.stretchedAreaRatio();
  if (compressed < kCompressedAreaRatio) return std::sqrt(std::max(compressed, 0.0) / kFittingCompressedRatio);
  if (stretched > kStretchedAreaRatio) return std::sqrt(stretched / kFittingStretchedRatio);
  return 1.0;
}

std::string fitAdvice(const Dressing& dressing) {
  const double grade = std::clamp(suggestedGrade(dressing), 0.6, 1.6);
  if (grade == 1.0) return {};
  const bool large = grade < 1.0;
  const std::string size = garment::nearestSize(grade);
  std::ostringstream s;
  s << std::setprecision(2) << "the garment is too " << (large ? "large" : "small")
    << " for this body: a twentieth of its cloth is " << (large ? "compressed to less than " : "stretched to more than ")
    << (large ? dressing.compressedAreaRatio() : dressing.stretchedAreaRatio()) << " of its pattern area (a fitting "
    << "garment keeps about " << (large ? kFittingCompressedRatio : kFittingStretchedRatio) << "; "
    << (large ? "below " : "above ") << (large ? kCompressedAreaRatio : kStretchedAreaRatio)
    << (large ? " it crumples on the body" : " it is stretched tight") << "); grade it by about "
    << std::setprecision(3) << grade << ": for the T-shirt template, `pixelcloth garment tshirt --grade " << grade
    << " --out DIR` (nearest size " << size << ", `--size " << size << "`); for an imported garment, a "
    << (large ? "smaller" : "larger") << " size of it";
  return s.str();
}

std::string Dressing::summary() const {
  const std::vector<double> before = log2Of(areaRatioBefore), after = log2Of(areaRatioAfter);
  std::ostringstream s;
  s << std::setprecision(3) << cageVertices.size() << " cage vertices, " << pushedVertices << " pushed out (max "
    << 100 * maxPenetration << " cm deep), " << relaxIterations
    << (relaxConverged ? " sweeps" : " sweeps, stopped at the cap before settling") << " (residual " << relaxResidual
    << " m), log2 area ratio 5-95% [" << core::quantile(before, 0.05) << ", " << core::quantile(before, 0.95)
    << "] -> [" << core::quantile(after, 0.05) << ", " << core::quantile(after, 0.95) << "]";
  return s.str();
}

Eigen::MatrixX3d patternUDirections(const garment::Garment& garment, const Eigen::MatrixX3d& positions) {
  const core::Mesh& mesh = garment.mesh;
  PIXELCLOTH_CHECK(positions.rows() == mesh.numVertices(), "patternUDirections: " << positions.rows()
                                                                                  << " positions for a garment of "
                                                                                  << mesh.numVertices() << " vertices");
  PIXELCLOTH_CHECK(mesh.hasUV() && garment.faceLayout.size() == mesh.numFaces() &&
                       garment.vertexUV.rows() == mesh.numVertices() && garment.vertexUV.cols() >= 1,
                   "patternUDirections: garment '" << garment.name << "' lacks UVs, face layouts or vertex UV rows");
  std::vector<int> firstLayout(mesh.numVertices(), -1);
  for (int v = 0; v < mesh.numVertices(); ++v) {
    for (int l = 0; l < garment.vertexUV.cols() && firstLayout[v] < 0; ++l) {
      if (garment.vertexUV(v, l) >= 0) firstLayout[v] = l;
    }
  }
  Eigen::MatrixX3d u = Eigen::MatrixX3d::Zero(mesh.numVertices(), 3);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(mesh.numVertices());
  for (int f = 0; f < mesh.numFaces(); ++f) {
    Eigen::Matrix2d uvEdges;
    uvEdges << (mesh.UV.row(mesh.FUV(f, 1)) - mesh.UV.row(mesh.FUV(f, 0))).transpose(),
        (mesh.UV.row(mesh.FUV(f, 2)) - mesh.UV.row(mesh.FUV(f, 0))).transpose();
    const double patternArea2 = uvEdges.determinant();
    if (std::abs(patternArea2) < 1e-16) continue;
    Eigen::Matrix<double, 3, 2> edges;
    edges << (positions.row(mesh.F(f, 1)) - positions.row(mesh.F(f, 0))).transpose(),
        (positions.row(mesh.F(f, 2)) - positions.row(mesh.F(f, 0))).transpose();
    const Eigen::Vector3d uAxis = (edges * uvEdges.inverse()).col(0);
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(f, k);
      if (garment.faceLayout[f] != firstLayout[v]) continue;
      u.row(v) += 0.5 * std::abs(patternArea2) * uAxis.transpose();
      weight[v] += 0.5 * std::abs(patternArea2);
    }
  }
  for (int v = 0; v < mesh.numVertices(); ++v) {
    if (weight[v] > 0) u.row(v) /= weight[v];
  }
  return u;
}

namespace {
/// A garment is dressed from where it sits: one more than 25 cm outside the body's box (another project's origin, another up
/// axis) would be morphed and carried across a metre of space, or, where nothing of it is morphed (the necktie),
/// left there. Refused, naming the move that would put it on the body.
void checkPlacement(const body::Body& body, const garment::Garment& garment) {
  const Eigen::AlignedBox3d cloth(garment.mesh.V.colwise().minCoeff().transpose(),
                                  garment.mesh.V.colwise().maxCoeff().transpose());
  const Eigen::AlignedBox3d skin(body.mesh.V.colwise().minCoeff().transpose(),
                                 body.mesh.V.colwise().maxCoeff().transpose());
  // A necktie hangs a few centimetres in front of the chest; a garment from another origin is a metre away.
  constexpr double kFarGap = 0.25;
  if (cloth.squaredExteriorDistance(skin) < kFarGap * kFarGap) return;
  const Eigen::Vector3d move = skin.center() - cloth.center();
  const Eigen::Vector3d size = cloth.sizes();
  std::ostringstream s;
  s << std::setprecision(3) << "dressing: garment '" << garment.name << "' (" << size.x() << " x " << size.y() << " x "
    << size.z() << " m, centred at " << cloth.center().transpose() << ") lies "
    << std::sqrt(cloth.squaredExteriorDistance(skin)) << " m outside the body's bounding box (centred at "
    << skin.center().transpose() << ")";
  if (size.z() > 1.5 * size.y()) s << " and lies along z (is the file Z-up? import it with --up z)";
  s << "; import it moved onto the body, e.g. `pixelcloth garment --import OBJ --translate " << move.x() << " "
    << move.y() << " " << move.z() << " ...`";
  PIXELCLOTH_FAIL(s.str());
}
}  // namespace

Dressing dressGarment(const body::Body& body, const Cage& bodyCage, const garment::Garment& garment,
                      const Cage& garmentCage, const DressingOptions& options) {
  options.validate();
  const core::Mesh& mesh = garment.mesh;
  const int n = mesh.numVertices();
  PIXELCLOTH_CHECK(n > 0 && mesh.hasUV(), "dressing: garment '" << garment.name << "' has no vertices or no UVs");
  PIXELCLOTH_CHECK(body.mesh.numFaces() > 0, "dressing: the body has no faces");
  mesh.validate("dressing: garment '" + garment.name + "'");
  garmentCage.validate(mesh.F, n, "dressing: garment cage of '" + garment.name + "'");
  bodyCage.validate(body.mesh.F, body.mesh.numVertices(), "dressing: body cage");
  checkPlacement(body, garment);

  const BodySurface surface(body);
  const PatternEdges patternEdges(garment);
  Dressing d;

  // 1. Cage morph and Poisson carry of its displacement.
  const std::map<int, Eigen::Vector3d> targets =
      morphCage(body, surface, bodyCage, garment, garmentCage, patternEdges, options.clearance);
  std::map<int, Eigen::Vector3d> fixedDisplacement;
  for (const auto& [v, p] : targets) {
    fixedDisplacement[v] = p - mesh.V.row(v).transpose();
    d.cageVertices.push_back(v);
  }
  d.morphed = mesh.V + harmonicDisplacement(mesh.V, mesh.F, fixedDisplacement);
  PIXELCLOTH_CHECK(d.morphed.allFinite(), "dressing: the Poisson carry of the cage morph is not finite");

  // 2. Push-out: vertices inside the body go to their closest body point, `clearance` outside.
  d.pushed = d.morphed;
  const std::vector<bool> inside = core::insideClosedMesh(body.mesh.V, body.mesh.F, d.morphed);
  std::vector<BodySurface::Hit> hits(n);
  std::vector<bool> haveHit(n, false);
  for (int v = 0; v < n; ++v) {
    if (!inside[v]) continue;
    hits[v] = surface.closest(d.morphed.row(v).transpose());
    haveHit[v] = true;
    d.maxPenetration = std::max(d.maxPenetration, (hits[v].point - d.morphed.row(v).transpose()).norm());
    d.pushed.row(v) = (hits[v].point + options.clearance * hits[v].normal).transpose();
    ++d.pushedVertices;
  }
  d.areaRatioBefore = core::areaRatios(d.pushed, garment.mesh);

  // 3. Relaxation (paper appendix): sweeps of edge-length equalisation, free vertices kept on the body.
  d.relaxed = d.pushed;
  if (!targets.empty()) {
    std::vector<bool> fixed(n, false);
    for (int v : d.cageVertices) fixed[v] = true;
    auto project = [&](int v, const Eigen::Vector3d& p) {
      hits[v] = haveHit[v] ? surface.closest(p, hits[v]) : surface.closest(p);
      haveHit[v] = true;
      return Eigen::Vector3d(hits[v].point + options.clearance * hits[v].normal);
    };
    // Shrink-wrap: every free vertex starts on the body.
    for (int v = 0; v < n; ++v) {
      if (!fixed[v]) d.relaxed.row(v) = project(v, d.relaxed.row(v).transpose()).transpose();
    }
    const auto& edges = patternEdges.edges;
    const int numEdges = static_cast<int>(edges.size());
    std::vector<int> degree(n, 0);
    for (const auto& [a, b] : edges) ++degree[a], ++degree[b];
    std::vector<int> freeIndex(n, -1);
    int numFree = 0;
    for (int v = 0; v < n; ++v) {
      if (!fixed[v] && degree[v] > 0) freeIndex[v] = numFree++;
    }
    // Oriented global steps: sum over face edges (i, j) of |x_j - x_i - t_ij|^2 with the cage vertices fixed; the
    // uniform Laplacian of the face edges is factorised once.
    const auto& F = mesh.F;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> global;
    if (!options.jacobiRelaxation && numFree > 0) {
      std::vector<Eigen::Triplet<double>> triplets;
      for (int f = 0; f < F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
          const int a = F(f, k), b = F(f, (k + 1) % 3);
          for (const auto& [p, q] : {std::pair<int, int>{a, b}, std::pair<int, int>{b, a}}) {
            if (freeIndex[p] < 0) continue;
            triplets.emplace_back(freeIndex[p], freeIndex[p], 1.0);
            if (freeIndex[q] >= 0) triplets.emplace_back(freeIndex[p], freeIndex[q], -1.0);
          }
        }
      }
      Eigen::SparseMatrix<double> L(numFree, numFree);
      L.setFromTriplets(triplets.begin(), triplets.end());
      global.compute(L);
      PIXELCLOTH_CHECK(global.info() == Eigen::Success,
                       "dressing: a piece of the garment has no cage vertex; the relaxation cannot be solved");
      for (int v = 0; v < n; ++v) {
        if (!haveHit[v]) project(v, d.relaxed.row(v).transpose());  // reference normals at the cage vertices too
      }
    }
    Eigen::VectorXd alpha(n), currentLength(numEdges);
    Eigen::MatrixX3d correction(n, 3), rhs(numFree, 3);
    d.relaxResidual = std::numeric_limits<double>::infinity();
    while (d.relaxIterations < options.maxRelaxIterations && d.relaxResidual >= options.relaxTolerance) {
      alpha.setZero();
      for (int e = 0; e < numEdges; ++e) {
        const auto [a, b] = edges[e];
        currentLength[e] = (d.relaxed.row(a) - d.relaxed.row(b)).norm();
        const double ratio = patternEdges.restLength[e] > 0 ? currentLength[e] / patternEdges.restLength[e] : 1.0;
        alpha[a] += ratio;
        alpha[b] += ratio;
      }
      for (int v = 0; v < n; ++v) alpha[v] /= std::max(degree[v], 1);
      Eigen::MatrixX3d proposed = d.relaxed;
      if (options.jacobiRelaxation) {
        // Per edge, the correction toward its target length, half to each end along the edge (a shortened edge
        // pushes its ends apart), averaged per vertex.
        correction.setZero();
        for (int e = 0; e < numEdges; ++e) {
          const auto [a, b] = edges[e];
          if (currentLength[e] <= 0) continue;
          const double target = 0.5 * (alpha[a] + alpha[b]) * patternEdges.restLength[e];
          const Eigen::RowVector3d move =
              0.5 * (currentLength[e] - target) / currentLength[e] * (d.relaxed.row(b) - d.relaxed.row(a));
          correction.row(a) += move;
          correction.row(b) -= move;
        }
        for (int v = 0; v < n; ++v) {
          if (freeIndex[v] >= 0) proposed.row(v) += correction.row(v) / degree[v];
        }
      } else {
        // Target edge vectors: the pattern edge, turned into the body's tangent plane by the face's best-fit rotation
        // (polar part of its deformation gradient there, a proper rotation about the body normal), scaled to
        // (alpha_a + alpha_b) / 2 times its rest length.
        rhs.setZero();
        for (int f = 0; f < F.rows(); ++f) {
          Eigen::Vector3d normal = Eigen::Vector3d::Zero();
          for (int k = 0; k < 3; ++k) normal += hits[F(f, k)].normal;
          normal.normalize();
          const Eigen::Vector3d t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
          Eigen::Matrix2d rest, current;
          for (int k = 1; k < 3; ++k) {
            rest.col(k - 1) = (mesh.UV.row(mesh.FUV(f, k)) - mesh.UV.row(mesh.FUV(f, 0))).transpose();
            const Eigen::Vector3d edge = (d.relaxed.row(F(f, k)) - d.relaxed.row(F(f, 0))).transpose();
            current.col(k - 1) = Eigen::Vector2d(edge.dot(t1), edge.dot(t2));
          }
          if (std::abs(rest.determinant()) < 1e-16) continue;
          const Eigen::JacobiSVD<Eigen::Matrix2d> svd(current * rest.inverse(),
                                                      Eigen::ComputeFullU | Eigen::ComputeFullV);
          Eigen::Matrix2d U = svd.matrixU();
          if ((U * svd.matrixV().transpose()).determinant() < 0) U.col(1) *= -1;
          const Eigen::Matrix2d rotation = U * svd.matrixV().transpose();
          for (int k = 0; k < 3; ++k) {
            const int a = F(f, k), b = F(f, (k + 1) % 3);
            const Eigen::Vector2d turned =
                rotation * (mesh.UV.row(mesh.FUV(f, (k + 1) % 3)) - mesh.UV.row(mesh.FUV(f, k))).transpose();
            const Eigen::RowVector3d target =
                0.5 * (alpha[a] + alpha[b]) * (turned.x() * t1 + turned.y() * t2).transpose();
            // Normal equations: deg(a) x_a - sum x_b = -sum t_ab, fixed neighbours moved to the right-hand side.
            if (freeIndex[a] >= 0) {
              rhs.row(freeIndex[a]) -= target;
              if (freeIndex[b] < 0) rhs.row(freeIndex[a]) += d.relaxed.row(b);
            }
            if (freeIndex[b] >= 0) {
              rhs.row(freeIndex[b]) += target;
              if (freeIndex[a] < 0) rhs.row(freeIndex[b]) += d.relaxed.row(a);
            }
          }
        }
        const Eigen::MatrixX3d solved = global.solve(rhs);
        for (int v = 0; v < n; ++v) {
          if (freeIndex[v] >= 0) proposed.row(v) = solved.row(freeIndex[v]);
        }
      }
      d.relaxResidual = 0;
      for (int v = 0; v < n; ++v) {
        if (freeIndex[v] < 0) continue;
        const Eigen::Vector3d moved = project(v, proposed.row(v).transpose());
        d.relaxResidual = std::max(d.relaxResidual, (moved - d.relaxed.row(v).transpose()).norm());
        proposed.row(v) = moved.transpose();
      }
      d.relaxed = std::move(proposed);
      ++d.relaxIterations;
    }
    if (d.relaxIterations == 0) d.relaxResidual = 0;
    d.relaxConverged = d.relaxResidual < options.relaxTolerance;
  }
  PIXELCLOTH_CHECK(d.relaxed.allFinite(), "dressing: the relaxed garment is not finite");
  d.areaRatioAfter = core::areaRatios(d.relaxed, garment.mesh);

  // 4. Embedding with the pattern's u axis on the dressed surface.
  d.embedding = garment::embedClosest(body.mesh.V, body.mesh.F, d.relaxed, patternUDirections(garment, d.relaxed));
  d.part = collisionPartOf(body, garment, d.embedding);
  return d;
}

}  // namespace pixelcloth::cage
