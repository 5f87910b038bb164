#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace pixelcloth::core {

/// The point of a mesh closest to a query: its face, barycentric coordinates in that face, position and distance.
struct MeshHit {
  int face = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0;  ///< Euclidean distance from the query, metres (>= 0)
};

/// One spatial index over a triangle mesh, built once and queried many times (the body of a frame, a collider):
/// closest point, segment intersection, and the inside test of a closed mesh. A CGAL AABB tree over the triangles
/// inside; the mesh may be open or non-manifold for the closest-point and segment queries.
class MeshIndex {
 public:
  /// `V` #V x 3, `F` #F x 3 (indices checked); both are copied.
  MeshIndex(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);
  ~MeshIndex();
  MeshIndex(MeshIndex&&) noexcept;
  MeshIndex& operator=(MeshIndex&&) noexcept;

  /// The closest point of the mesh to `p` (exact).
  MeshHit closest(const Eigen::Vector3d& p) const;
  /// The same, the search started from `near` (an earlier answer for a point nearby): much faster for small moves.
  MeshHit closest(const Eigen::Vector3d& p, const MeshHit& near) const;
  /// True when the segment [a, b] meets a triangle of the mesh.
  bool intersects(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
  /// How many triangles the ray from `p` along `direction` meets: odd inside a closed mesh, whether or not it
  /// passes through itself, where the pseudo-normal test sees only the nearest sheet.
  int crossings(const Eigen::Vector3d& p, const Eigen::Vector3d& direction) const;
  /// For a closed, outward-oriented mesh: true where `p` is strictly inside, by the pseudo-normal test of Baerentzen
  /// and Aanaes (2005) at the closest point (exact for closed meshes).
  bool inside(const Eigen::Vector3d& p) const;
  /// The same with `p`'s closest point `closest` (from closest(p)) already found.
  bool inside(const Eigen::Vector3d& p, const MeshHit& closest) const;
  /// inside() for every row of `P` (#P x 3).
  std::vector<bool> inside(const Eigen::MatrixX3d& P) const;
  /// Unit normal at a point of face `face` with barycentric coordinates `barycentric`: the blend of the area-weighted
  /// vertex normals (smooth across edges), the face normal where that blend vanishes.
  Eigen::Vector3d smoothNormal(int face, const Eigen::Vector3d& barycentric) const;

  const Eigen::MatrixX3d& vertices() const;
  const Eigen::MatrixX3i& faces() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One-shot inside test: true where rows of `P` (#P x 3) lie inside the closed mesh (V, F).
std::vector<bool> insideClosedMesh(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& P);

}  // namespace pixelcloth::core
