#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace pixelcloth::core {

/// The pairs of faces of the triangle mesh (V, F) that intersect each other, each pair (f, g) with f < g, sorted.
/// Faces that share a vertex or an edge count only where they overlap beyond it (CGAL's
/// Polygon_mesh_processing::self_intersections, exact predicates). For cloth, a simulated garment that passes through
/// itself. Throws InputError when F is not a manifold mesh over V.
std::vector<std::pair<int, int>> selfIntersections(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

}  // namespace pixelcloth::core
