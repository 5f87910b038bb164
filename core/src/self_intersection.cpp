#include "pixelcloth/core/self_intersection.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>

#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

std::vector<std::pair<int, int>> selfIntersections(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SurfaceMesh = CGAL::Surface_mesh<Epick::Point_3>;
  PIXELCLOTH_CHECK(V.allFinite(), "self-intersections: a vertex position is not finite");
  SurfaceMesh mesh;
  for (int v = 0; v < V.rows(); ++v) mesh.add_vertex(Epick::Point_3(V(v, 0), V(v, 1), V(v, 2)));
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k)
      PIXELCLOTH_CHECK(F(f, k) >= 0 && F(f, k) < V.rows(),
                       "self-intersections: face " << f + 1 << " names vertex " << F(f, k) + 1 << " of " << V.rows());
    const SurfaceMesh::Face_index face = mesh.add_face(
        SurfaceMesh::Vertex_index(F(f, 0)), SurfaceMesh::Vertex_index(F(f, 1)), SurfaceMesh::Vertex_index(F(f, 2)));
    PIXELCLOTH_CHECK(face != SurfaceMesh::null_face(),
                     "self-intersections: face " << f + 1 << " makes the mesh non-manifold; expected a manifold mesh");
  }
  std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> found;
  CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(found));
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(found.size());
  for (const auto& [a, b] : found) {
    const int f = static_cast<int>(a), g = static_cast<int>(b);
    pairs.emplace_back(std::min(f, g), std::max(f, g));
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace pixelcloth::core
