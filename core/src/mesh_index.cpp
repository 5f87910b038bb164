#include "pixelcloth/core/mesh_index.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Geometry>
#include <cmath>
#include <mutex>

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

/// What the inside test needs beyond the tree: the faces around each vertex (built on first use), from which the
/// pseudo-normals of faces, edges and vertices are made when a query needs them.
struct VertexFaces {
  std::vector<int> start, faces;  ///< the faces of vertex v are faces[start[v] .. start[v + 1])
};

struct MeshIndex::Impl {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  std::vector<Triangle> triangles;
  Tree tree;
  mutable std::once_flag adjacencyOnce, smoothOnce;
  mutable VertexFaces adjacency;
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

  const VertexFaces& vertexFaces() const {
    std::call_once(adjacencyOnce, [this] {
      adjacency.start.assign(V.rows() + 1, 0);
      for (Eigen::Index i = 0; i < F.size(); ++i) ++adjacency.start[F.data()[i] + 1];
      for (Eigen::Index v = 0; v < V.rows(); ++v) adjacency.start[v + 1] += adjacency.start[v];
      adjacency.faces.resize(F.size());
      std::vector<int> next(adjacency.start.begin(), adjacency.start.end() - 1);
      for (int f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) adjacency.faces[next[F(f, k)]++] = f;
    });
    return adjacency;
  }

  /// Unit normal of face f (zero for a degenerate face).
  Eigen::Vector3d faceNormal(int f) const {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double length = n.norm();
    return length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
  }

  /// The pseudo-normal of edge (a, b): the sum of the normals of the faces around it.
  Eigen::Vector3d edgeNormal(int a, int b) const {
    const VertexFaces& around = vertexFaces();
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int i = around.start[a]; i < around.start[a + 1]; ++i) {
      const int f = around.faces[i];
      if (F(f, 0) == b || F(f, 1) == b || F(f, 2) == b) n += faceNormal(f);
    }
    return n;
  }

  /// The pseudo-normal of vertex v: the normals of its faces weighted by their angles at v.
  Eigen::Vector3d vertexNormal(int v) const {
    const VertexFaces& around = vertexFaces();
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int i = around.start[v]; i < around.start[v + 1]; ++i) {
      const int f = around.faces[i];
      const int k = F(f, 0) == v ? 0 : F(f, 1) == v ? 1 : 2;
      const Eigen::Vector3d p = V.row(v), e1 = V.row(F(f, (k + 1) % 3)).transpose() - p,
                            e2 = V.row(F(f, (k + 2) % 3)).transpose() - p;
      n += std::atan2(e1.cross(e2).norm(), e1.dot(e2)) * faceNormal(f);
    }
    return n;
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

int MeshIndex::crossings(const Eigen::Vector3d& p, const Eigen::Vector3d& direction) const {
  return static_cast<int>(impl_->tree.number_of_intersected_primitives(
      Kernel::Ray_3(toPoint(p), Kernel::Direction_3(direction.x(), direction.y(), direction.z()))));
}

bool MeshIndex::inside(const Eigen::Vector3d& p) const { return inside(p, closest(p)); }

bool MeshIndex::inside(const Eigen::Vector3d& p, const MeshHit& h) const {
  const Eigen::MatrixX3i& F = impl_->F;
  // The pseudo-normal of the closest feature: the face's in its interior, the edge's on an edge, the vertex's at a
  // corner (Baerentzen and Aanaes 2005).
  int zeros = 0, zero = 0, corner = 0;
  for (int k = 0; k < 3; ++k) {
    if (h.barycentric(k) <= 1e-12) ++zeros, zero = k;
    if (h.barycentric(k) > h.barycentric(corner)) corner = k;
  }
  Eigen::Vector3d normal;
  if (zeros == 1)
    normal = impl_->edgeNormal(F(h.face, (zero + 1) % 3), F(h.face, (zero + 2) % 3));
  else if (zeros == 2)
    normal = impl_->vertexNormal(F(h.face, corner));
  else
    normal = impl_->faceNormal(h.face);
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
