#include "pixelcloth/core/mesh_index.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Geometry>
#include <cmath>
#include <mutex>
#include <unordered_map>

#include "pixelcloth/core/edge_key.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh.h"

namespace pixelcloth::core {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>>>;

Point toPoint(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

/// What the inside test needs beyond the tree: the pseudo-normals of faces, edges and vertices (built on first use).
struct PseudoNormals {
  Eigen::MatrixX3d face, vertex;                            ///< unit face normals; angle-weighted vertex normals
  std::unordered_map<std::uint64_t, Eigen::Vector3d> edge;  ///< sum of the normals of the faces around an edge
};

struct MeshIndex::Impl {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  std::vector<Triangle> triangles;
  Tree tree;
  mutable std::once_flag pseudoOnce, smoothOnce;
  mutable PseudoNormals pseudo;
  mutable Eigen::MatrixX3d smooth;  ///< area-weighted vertex normals, built on the first smoothNormal query

  const Eigen::MatrixX3d& smoothNormals() const {
    std::call_once(smoothOnce, [this] { smooth = vertexNormals(V, F); });
    return smooth;
  }

  MeshHit hit(int f, const Eigen::Vector3d& p) const {
    MeshHit h;
    h.face = f;
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    h.barycentric = closestPointOnTriangle(p, a, b, c);
    h.point = h.barycentric(0) * a + h.barycentric(1) * b + h.barycentric(2) * c;
    h.distance = (p - h.point).norm();
    return h;
  }
  int faceOf(TriangleIterator it) const { return static_cast<int>(it - triangles.cbegin()); }

  const PseudoNormals& pseudoNormals() const {
    std::call_once(pseudoOnce, [this] {
      pseudo.face = faceNormals(V, F);
      pseudo.vertex = Eigen::MatrixX3d::Zero(V.rows(), 3);
      for (int f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector3d p = V.row(F(f, k)), e1 = V.row(F(f, (k + 1) % 3)).transpose() - p,
                                e2 = V.row(F(f, (k + 2) % 3)).transpose() - p;
          pseudo.vertex.row(F(f, k)) += std::atan2(e1.cross(e2).norm(), e1.dot(e2)) * pseudo.face.row(f);
          auto [it, fresh] = pseudo.edge.try_emplace(edgeKey(F(f, k), F(f, (k + 1) % 3)), Eigen::Vector3d::Zero());
          it->second += pseudo.face.row(f).transpose();
        }
    });
    return pseudo;
  }
};

MeshIndex::MeshIndex(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) : impl_(std::make_unique<Impl>()) {
  PIXELCLOTH_CHECK(F.rows() > 0, "spatial index: the mesh has no faces");
  PIXELCLOTH_CHECK(F.minCoeff() >= 0 && F.maxCoeff() < V.rows(),
                   "spatial index: a face uses a vertex outside [0, " << V.rows() << ")");
  impl_->V = V;
  impl_->F = F;
  impl_->triangles.reserve(F.rows());
  for (int f = 0; f < F.rows(); ++f)
    impl_->triangles.emplace_back(toPoint(V.row(F(f, 0))), toPoint(V.row(F(f, 1))), toPoint(V.row(F(f, 2))));
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  // The tree now; the k-d tree that seeds a query without a hint only on the first such query (CGAL builds it then,
  // under a lock): a caller that always passes a hint, as the simulator's contacts do, never pays for it.
  impl_->tree.build();
}

MeshIndex::~MeshIndex() = default;
MeshIndex::MeshIndex(MeshIndex&&) noexcept = default;
MeshIndex& MeshIndex::operator=(MeshIndex&&) noexcept = default;

MeshHit MeshIndex::closest(const Eigen::Vector3d& p) const {
  return impl_->hit(impl_->faceOf(impl_->tree.closest_point_and_primitive(toPoint(p)).second), p);
}

MeshHit MeshIndex::closest(const Eigen::Vector3d& p, const MeshHit& near) const {
  PIXELCLOTH_CHECK(near.face >= 0 && near.face < impl_->F.rows(),
                   "spatial index: hint face " << near.face << " is outside [0, " << impl_->F.rows() << ")");
  const auto hint = std::make_pair(toPoint(near.point), impl_->triangles.cbegin() + near.face);
  return impl_->hit(impl_->faceOf(impl_->tree.closest_point_and_primitive(toPoint(p), hint).second), p);
}

bool MeshIndex::intersects(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  return impl_->tree.do_intersect(Kernel::Segment_3(toPoint(a), toPoint(b)));
}

bool MeshIndex::inside(const Eigen::Vector3d& p) const {
  const MeshHit h = closest(p);
  const PseudoNormals& pseudo = impl_->pseudoNormals();
  const Eigen::MatrixX3i& F = impl_->F;
  // The pseudo-normal of the closest feature: the face's in its interior, the edge's on an edge, the vertex's at a
  // corner (Baerentzen and Aanaes 2005).
  int zeros = 0, zero = 0, corner = 0;
  for (int k = 0; k < 3; ++k) {
    if (h.barycentric(k) <= 1e-12) ++zeros, zero = k;
    if (h.barycentric(k) > h.barycentric(corner)) corner = k;
  }
  Eigen::Vector3d normal = pseudo.face.row(h.face).transpose();
  if (zeros == 1) {
    const auto it = pseudo.edge.find(edgeKey(F(h.face, (zero + 1) % 3), F(h.face, (zero + 2) % 3)));
    if (it != pseudo.edge.end()) normal = it->second;
  } else if (zeros == 2) {
    normal = pseudo.vertex.row(F(h.face, corner)).transpose();
  }
  return (p - h.point).dot(normal) < 0;
}

std::vector<bool> MeshIndex::inside(const Eigen::MatrixX3d& P) const {
  std::vector<bool> result(P.rows());
  for (int i = 0; i < P.rows(); ++i) result[i] = inside(Eigen::Vector3d(P.row(i).transpose()));
  return result;
}

Eigen::Vector3d MeshIndex::smoothNormal(int face, const Eigen::Vector3d& barycentric) const {
  const Eigen::MatrixX3d& V = impl_->V;
  const Eigen::MatrixX3i& F = impl_->F;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) normal += barycentric[k] * impl_->smoothNormals().row(F(face, k)).transpose();
  if (normal.norm() < 1e-12)
    normal = (V.row(F(face, 1)) - V.row(F(face, 0))).cross(V.row(F(face, 2)) - V.row(F(face, 0))).transpose();
  return normal.normalized();
}

const Eigen::MatrixX3d& MeshIndex::vertices() const { return impl_->V; }
const Eigen::MatrixX3i& MeshIndex::faces() const { return impl_->F; }

std::vector<bool> insideClosedMesh(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& P) {
  return MeshIndex(V, F).inside(P);
}

}  // namespace pixelcloth::core
