// Rest lengths of cage curves: pattern-space and 3D polyline arc lengths, and exact surface geodesics (CGAL).
#include "pixelcloth/cage/geodesic.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <limits>

#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::cage {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Traits = CGAL::Surface_mesh_shortest_path_traits<Kernel, SurfaceMesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;
}  // namespace

namespace {
const core::EnumNames<RestLengths, 3> kRestLengths{
    "rest lengths",
    {{{RestLengths::Pattern, "pattern"}, {RestLengths::Polyline, "polyline"}, {RestLengths::Geodesic, "geodesic"}}}};
}  // namespace

const char* restLengthsName(RestLengths lengths) { return kRestLengths.name(lengths); }

RestLengths restLengthsFromName(const std::string& name, const std::string& context) {
  return kRestLengths.fromName(name, context);
}

double patternEdgeLength(const garment::Garment& garment, int a, int b) {
  const int n = garment.mesh.numVertices();
  PIXELCLOTH_CHECK(a >= 0 && b >= 0 && a < n && b < n,
                   garment.name << ": edge (" << a << ", " << b << ") out of range for " << n << " vertices");
  for (int l = 0; l < garment.numLayouts(); ++l) {
    const int ua = garment.vertexUV(a, l), ub = garment.vertexUV(b, l);
    if (ua >= 0 && ub >= 0) return (garment.mesh.UV.row(ua) - garment.mesh.UV.row(ub)).norm();
  }
  PIXELCLOTH_FAIL(garment.name << ": vertices " << a << " and " << b << " share no layout, so the edge has no "
                               << "pattern-space length");
}

std::vector<double> patternArcLengths(const garment::Garment& garment, const CageCurve& curve) {
  const size_t n = curve.vertices.size();
  std::vector<double> s(1, 0.0);
  for (size_t i = 1; i < n + (curve.closed ? 1 : 0); ++i)
    s.push_back(s.back() + patternEdgeLength(garment, curve.vertices[i - 1], curve.vertices[i % n]));
  return s;
}

std::vector<double> polylineArcLengths(const Eigen::Ref<const Eigen::MatrixX3d>& V, const CageCurve& curve) {
  const size_t n = curve.vertices.size();
  std::vector<double> s(1, 0.0);
  for (size_t i = 1; i < n + (curve.closed ? 1 : 0); ++i) {
    const int a = curve.vertices[i - 1], b = curve.vertices[i % n];
    PIXELCLOTH_CHECK(a >= 0 && b >= 0 && a < V.rows() && b < V.rows(),
                     "curve '" << curve.name << "': vertex out of range for " << V.rows() << " positions");
    s.push_back(s.back() + (V.row(a) - V.row(b)).norm());
  }
  return s;
}

struct GeodesicDistance::Impl {
  SurfaceMesh mesh;
  std::vector<SurfaceMesh::Vertex_index> vertices;
};

GeodesicDistance::GeodesicDistance(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F)
    : impl_(std::make_unique<Impl>()) {
  for (int v = 0; v < V.rows(); ++v)
    impl_->vertices.push_back(impl_->mesh.add_vertex(Point(V(v, 0), V(v, 1), V(v, 2))));
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k)
      PIXELCLOTH_CHECK(F(f, k) >= 0 && F(f, k) < V.rows(),
                       "geodesics: face " << f << " uses vertex " << F(f, k) << ", but there are " << V.rows());
    const auto face =
        impl_->mesh.add_face(impl_->vertices[F(f, 0)], impl_->vertices[F(f, 1)], impl_->vertices[F(f, 2)]);
    PIXELCLOTH_CHECK(face != SurfaceMesh::null_face(), "geodesics: face " << f << " makes the mesh non-manifold");
  }
}

GeodesicDistance::~GeodesicDistance() = default;
GeodesicDistance::GeodesicDistance(GeodesicDistance&&) noexcept = default;
GeodesicDistance& GeodesicDistance::operator=(GeodesicDistance&&) noexcept = default;

std::vector<double> GeodesicDistance::from(int source, const std::vector<int>& targets) const {
  const int n = static_cast<int>(impl_->vertices.size());
  PIXELCLOTH_CHECK(source >= 0 && source < n, "geodesics: source vertex " << source << " out of range (" << n << ")");
  ShortestPath paths(impl_->mesh);
  paths.add_source_point(impl_->vertices[source]);
  std::vector<double> out;
  out.reserve(targets.size());
  for (int t : targets) {
    PIXELCLOTH_CHECK(t >= 0 && t < n, "geodesics: target vertex " << t << " out of range (" << n << ")");
    const auto result = paths.shortest_distance_to_source_points(impl_->vertices[t]);
    out.push_back(result.first < 0 ? std::numeric_limits<double>::infinity() : result.first);
  }
  return out;
}

}  // namespace pixelcloth::cage
