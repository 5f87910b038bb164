// Exact surface geodesics (CGAL's Surface_mesh_shortest_path).
#include "pixelcloth/core/geodesic.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <limits>

#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Traits = CGAL::Surface_mesh_shortest_path_traits<Kernel, SurfaceMesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;
}  // namespace

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

}  // namespace pixelcloth::core
