#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace pixelcloth::core {

/// Exact geodesic distances on a triangle mesh (CGAL's Surface_mesh_shortest_path, the Xin-Wang / MMP window
/// propagation): built once per mesh, one source at a time. The mesh may have boundaries; it must be a manifold.
class GeodesicDistance {
 public:
  /// `V` #V x 3 metres, `F` #F x 3. Throws InputError for indices out of range.
  GeodesicDistance(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);
  ~GeodesicDistance();
  GeodesicDistance(GeodesicDistance&&) noexcept;
  GeodesicDistance& operator=(GeodesicDistance&&) noexcept;

  /// Shortest-path distances over the surface from vertex `source` to each of `targets`, metres (infinity for a
  /// vertex in another connected component).
  std::vector<double> from(int source, const std::vector<int>& targets) const;
  /// Distance between two vertices.
  double between(int a, int b) const { return from(a, {b}).front(); }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pixelcloth::core
