// The built-in mannequin: an implicit surface (smooth union of round cones and ellipsoids) meshed by
// CGAL's surface mesher, with the standard skeleton and bone-heat skin weights.
#include <CGAL/Complex_2_in_triangulation_3.h>
#include <CGAL/IO/facets_in_complex_2_to_triangle_mesh.h>
#include <CGAL/Implicit_surface_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_default_triangulation_3.h>
#include <CGAL/make_surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"

namespace pixelcloth::body {

using namespace core;

namespace {

using Vec = Eigen::Vector3d;

/// Polynomial smooth minimum (Quilez): blends two distance fields over a band of width k.
double smoothMin(double a, double b, double k) {
  double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

/// Approximate signed distance to a round cone from a (radius ra) to b (radius rb).
double roundCone(const Vec& p, const Vec& a, double ra, const Vec& b, double rb) {
  Vec ab = b - a;
  double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm() - (ra + t * (rb - ra));
}

/// Approximate signed distance to an axis-aligned ellipsoid (Quilez's bound).
double ellipsoid(const Vec& p, const Vec& centre, const Vec& radii) {
  Vec q = p - centre;
  double k0 = q.cwiseQuotient(radii).norm();
  double k1 = q.cwiseQuotient(radii.cwiseProduct(radii)).norm();
  if (k1 == 0) return -radii.minCoeff();
  return k0 * (k0 - 1.0) / k1;
}

/// The mannequin's distance field, metres; negative inside. `girth` scales torso depth/width and arms.
struct MannequinField {
  double girth = 1.0;

  double arm(const Vec& p, double side) const {
    double g = girth;
    double deltoid = ellipsoid(p, {side * 0.185, 1.405, -0.015}, {0.075, 0.07 * g, 0.065 * g});
    double upper = roundCone(p, {side * 0.17, 1.405, -0.015}, 0.058 * g, {side * 0.46, 1.42, -0.02}, 0.043 * g);
    double fore = roundCone(p, {side * 0.46, 1.42, -0.02}, 0.043 * g, {side * 0.71, 1.42, -0.02}, 0.030 * g);
    double hand = ellipsoid(p, {side * 0.80, 1.415, -0.02}, {0.095, 0.024 * std::sqrt(g), 0.047 * std::sqrt(g)});
    return smoothMin(smoothMin(smoothMin(deltoid, upper, 0.04), fore, 0.02), hand, 0.025);
  }

  double operator()(const Vec& p) const {
    double g = girth;
    double pelvis = ellipsoid(p, {0, 0.86, -0.005}, {0.165 * g, 0.13, 0.105 * g});
    double abdomen = ellipsoid(p, {0, 1.05, 0.0}, {0.14 * g, 0.16, 0.095 * g});
    double chest = ellipsoid(p, {0, 1.27, 0.005}, {0.165 * g, 0.16, 0.11 * g});
    double girdle = roundCone(p, {-0.16, 1.385, -0.015}, 0.062 * g, {0.16, 1.385, -0.015}, 0.062 * g);
    double torso = smoothMin(smoothMin(smoothMin(pelvis, abdomen, 0.08), chest, 0.09), girdle, 0.07);
    double neck = roundCone(p, {0, 1.40, -0.015}, 0.06, {0, 1.60, 0.0}, 0.052);
    double head = ellipsoid(p, {0, 1.655, 0.01}, {0.08, 0.095, 0.095});
    double upper = smoothMin(smoothMin(torso, neck, 0.05), head, 0.03);
    return smoothMin(smoothMin(upper, arm(p, 1.0), 0.035), arm(p, -1.0), 0.035);
  }
};

using Tr = CGAL::Surface_mesh_default_triangulation_3;
using C2t3 = CGAL::Complex_2_in_triangulation_3<Tr>;
using GT = Tr::Geom_traits;
using CgalPoint = GT::Point_3;
using CgalSphere = GT::Sphere_3;

/// Adapter from our field to the function object CGAL's Implicit_surface_3 expects.
struct CgalField {
  MannequinField field;
  GT::FT operator()(const CgalPoint& p) const { return field(Vec(p.x(), p.y(), p.z())); }
};

/// The mesher's output order follows memory addresses, and its coordinates can differ in the last bit
/// between runs: round to 0.1 micrometre and sort vertices and faces so the same options give the same mesh.
void canonicalise(Mesh& mesh) {
  const int n = mesh.numVertices();
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) mesh.V(i, k) = std::round(mesh.V(i, k) * 1e7) / 1e7;
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::make_tuple(mesh.V(a, 1), mesh.V(a, 0), mesh.V(a, 2)) <
           std::make_tuple(mesh.V(b, 1), mesh.V(b, 0), mesh.V(b, 2));
  });
  std::vector<int> newIndex(n);
  Eigen::MatrixX3d V(n, 3);
  for (int i = 0; i < n; ++i) {
    newIndex[order[i]] = i;
    V.row(i) = mesh.V.row(order[i]);
  }
  std::vector<std::array<int, 3>> faces(mesh.numFaces());
  for (int f = 0; f < mesh.numFaces(); ++f) {
    std::array<int, 3> face = {newIndex[mesh.F(f, 0)], newIndex[mesh.F(f, 1)], newIndex[mesh.F(f, 2)]};
    // Rotate (keeping orientation) so the smallest index comes first.
    while (face[0] > face[1] || face[0] > face[2]) face = {face[1], face[2], face[0]};
    faces[f] = face;
  }
  std::sort(faces.begin(), faces.end());
  mesh.V = V;
  for (int f = 0; f < mesh.numFaces(); ++f) mesh.F.row(f) << faces[f][0], faces[f][1], faces[f][2];
}

}  // namespace

void MannequinOptions::validate() const {
  PIXELCLOTH_CHECK(std::isfinite(shape) && shape >= -1.0 && shape <= 2.0,
                   "body shape must be in [-1, 2] (-1 thinner, 0 default, 2 thicker), got " << shape);
  PIXELCLOTH_CHECK(std::isfinite(edgeLength) && edgeLength >= 0.004 && edgeLength <= 0.1,
                   "mannequin edge length must be in [0.004, 0.1] m, got " << edgeLength);
}

Skeleton mannequinSkeleton() {
  Skeleton s;
  s.names = standardJointNames();
  s.parents = standardJointParents();
  s.positions.resize(12, 3);
  s.positions << 0, 0.92, -0.01,  // root (pelvis, fixed)
      0, 1.00, -0.01,             // lower_back
      0, 1.12, -0.01,             // spine
      0, 1.26, -0.01,             // spine1
      0, 1.46, -0.015,            // neck
      0, 1.58, 0.0,               // head (fixed)
      0.035, 1.40, -0.015,        // l_shoulder (sternoclavicular)
      0.175, 1.41, -0.015,        // l_arm (glenohumeral)
      0.46, 1.42, -0.02,          // l_forearm (elbow)
      -0.035, 1.40, -0.015,       // r_shoulder
      -0.175, 1.41, -0.015,       // r_arm
      -0.46, 1.42, -0.02;         // r_forearm
  s.boneEnds.resize(12, 3);
  s.boneEnds << s.positions.row(1), s.positions.row(2), s.positions.row(3), s.positions.row(4), s.positions.row(5), 0,
      1.72, 0.01,                                                  // head tip
      s.positions.row(7), s.positions.row(8), 0.86, 1.415, -0.02,  // left hand tip
      s.positions.row(10), s.positions.row(11), -0.86, 1.415, -0.02;
  return s;
}

Body makeMannequin(const MannequinOptions& options) {
  options.validate();
  CgalField function{MannequinField{1.0 + 0.12 * options.shape}};
  // Fixed seed: the mesher's initial points come from CGAL's default random generator.
  CGAL::get_default_random() = CGAL::Random(20181204);
  Tr triangulation;
  C2t3 complex(triangulation);
  CGAL::Implicit_surface_3<GT, CgalField> surface(function, CgalSphere(CgalPoint(0, 1.25, 0), 1.0), 1e-7);
  CGAL::Surface_mesh_default_criteria_3<Tr> criteria(30.0, options.edgeLength, options.edgeLength * 0.15);
  CGAL::make_surface_mesh(complex, surface, criteria, CGAL::Manifold_tag(), 20);
  CGAL::Surface_mesh<CgalPoint> surfaceMesh;
  CGAL::facets_in_complex_2_to_triangle_mesh(complex, surfaceMesh);

  Body body;
  Mesh& mesh = body.mesh;
  mesh.V.resize(surfaceMesh.number_of_vertices(), 3);
  std::vector<int> index(surfaceMesh.number_of_vertices());
  int next = 0;
  for (auto v : surfaceMesh.vertices()) {
    const CgalPoint& p = surfaceMesh.point(v);
    index[v.idx()] = next;
    mesh.V.row(next++) << p.x(), p.y(), p.z();
  }
  mesh.F.resize(surfaceMesh.number_of_faces(), 3);
  int f = 0;
  for (auto face : surfaceMesh.faces()) {
    int k = 0;
    for (auto v : CGAL::vertices_around_face(surfaceMesh.halfedge(face), surfaceMesh)) mesh.F(f, k++) = index[v.idx()];
    ++f;
  }
  if (enclosedVolume(mesh.V, mesh.F) < 0) mesh.F.col(1).swap(mesh.F.col(2));
  canonicalise(mesh);
  TopologyReport topology = checkTopology(mesh.numVertices(), mesh.F);
  PIXELCLOTH_CHECK(topology.closedManifold() && topology.components == 1,
                   "mannequin: the surface mesher produced a mesh that is not one closed manifold ("
                       << topology.firstProblem << "); try another edge length");

  body.skeleton = mannequinSkeleton();
  body.weights = boneHeatWeights(mesh.V, mesh.F, body.skeleton);
  body.parts = collisionParts(body);
  return body;
}

}  // namespace pixelcloth::body
