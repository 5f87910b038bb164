#pragma once
// Closest points on a body part (a collider) for the cloth solvers: an exact inside test by pseudo-normals, a local
// walk over the part's faces for small moves and an AABB tree for the rest. Private to sim/.

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <vector>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/geometry.h"
#include "pixelcloth/core/mesh_index.h"
#include "pixelcloth/sim/quasistatic.h"

namespace pixelcloth::sim::detail {

/// The point of a collider closest to a cloth vertex, and the contact it makes there.
struct Closest {
  int face = -1;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();  ///< of the closest point in `face`
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /// Outside: the unit direction from the closest point to the vertex (smooth across edges and corners); inside
  /// (behind the face's plane): the face normal.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double distance = 0;  ///< signed along `normal`: the Euclidean distance outside, the depth below the plane inside
  double squared = 0;   ///< squared Euclidean distance (what the searches minimise)
};

/// A collider with what the contact searches need: face normals (and, at a corner, the angle-weighted vertex normal,
/// computed when asked: corners are rare, and the normals of every vertex cost more per pose than all those asked),
/// the faces around each vertex and across each edge (the local walk), and an AABB tree (global queries, rebuilt
/// lazily after the vertices move).
struct ColliderState {
  Collider mesh;
  Eigen::MatrixX3d normals;                ///< per face
  std::vector<int> ringStart, ringFaces;   ///< faces around vertex v: ringFaces[ringStart[v] .. ringStart[v + 1])
  std::vector<int> across;                 ///< 3 f + k: the face across the edge opposite corner k of f, or -1
  std::vector<bool> onBoundary;            ///< per vertex: on an edge with one face (body parts are open meshes)
  std::unique_ptr<core::MeshIndex> index;  ///< built on first use after the vertices move

  explicit ColliderState(Collider collider) : mesh(std::move(collider)) {
    const int nv = static_cast<int>(mesh.V.rows()), nf = static_cast<int>(mesh.F.rows());
    ringStart.assign(nv + 1, 0);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) ++ringStart[mesh.F(f, k) + 1];
    for (int v = 0; v < nv; ++v) ringStart[v + 1] += ringStart[v];
    ringFaces.resize(3 * nf);
    std::vector<int> cursor(ringStart.begin(), ringStart.end() - 1);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) ringFaces[cursor[mesh.F(f, k)]++] = f;
    across.assign(3 * nf, -1);
    onBoundary.assign(nv, false);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.F(f, (k + 1) % 3), b = mesh.F(f, (k + 2) % 3);
        for (int i = ringStart[a]; i < ringStart[a + 1] && across[3 * f + k] < 0; ++i) {
          const int g = ringFaces[i];
          if (g != f && (mesh.F(g, 0) == b || mesh.F(g, 1) == b || mesh.F(g, 2) == b)) across[3 * f + k] = g;
        }
        if (across[3 * f + k] < 0) onBoundary[a] = onBoundary[b] = true;
      }
    moved();
  }

  void moved() {
    normals = core::faceNormals(mesh.V, mesh.F);
    index.reset();
  }

  /// The angle-weighted pseudo-normal of vertex v (unnormalised): each face's normal times its angle at v.
  Eigen::Vector3d vertexNormal(int v) const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = ringStart[v]; i < ringStart[v + 1]; ++i) {
      const int f = ringFaces[i];
      const int k = mesh.F(f, 0) == v ? 0 : mesh.F(f, 1) == v ? 1 : 2;
      const Eigen::Vector3d p = mesh.V.row(v), e1 = mesh.V.row(mesh.F(f, (k + 1) % 3)).transpose() - p,
                            e2 = mesh.V.row(mesh.F(f, (k + 2) % 3)).transpose() - p;
      sum += std::atan2(e1.cross(e2).norm(), e1.dot(e2)) * normals.row(f).transpose();
    }
    return sum;
  }

  /// Closest point of face f to p, with the inside test of Baerentzen and Aanaes (2005): p is inside when it lies
  /// behind the pseudo-normal of the closest feature (the face normal in the interior, the sum of both face normals
  /// on an edge, the angle-weighted normal at a corner), which is exact for closed meshes. Where the closest point is
  /// on the rim of an open part (where an arm meets the torso), p lies beyond the part's opening: outside.
  Closest onFace(int f, const Eigen::Vector3d& p) const {
    Closest c;
    c.face = f;
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), d = mesh.V.row(mesh.F(f, 2));
    c.bary = core::closestPointOnTriangle(p, a, b, d);
    c.point = c.bary(0) * a + c.bary(1) * b + c.bary(2) * d;
    const Eigen::Vector3d away = p - c.point;
    c.squared = away.squaredNorm();
    int zeros = 0, zero = -1, corner = 0;
    for (int k = 0; k < 3; ++k) {
      if (c.bary(k) <= 1e-12) ++zeros, zero = k;
      if (c.bary(k) > c.bary(corner)) corner = k;
    }
    Eigen::Vector3d pseudo = normals.row(f).transpose();
    bool rim = false;
    if (zeros == 1) {
      const int g = across[3 * f + zero];
      rim = g < 0;
      if (!rim) pseudo += normals.row(g).transpose();
    } else if (zeros == 2) {
      rim = onBoundary[mesh.F(f, corner)];
      pseudo = vertexNormal(mesh.F(f, corner));
    }
    const double length = std::sqrt(c.squared);
    const bool inside = !rim && away.dot(pseudo) < 0;
    c.distance = inside ? -length : length;
    if (length > 1e-12)
      c.normal = (inside ? -away : away) / length;
    else
      c.normal = pseudo.normalized();
    return c;
  }

  /// The AABB tree of the current placement, built on first use after the vertices moved.
  const core::MeshIndex& tree() {
    if (!index) index = std::make_unique<core::MeshIndex>(mesh.V, mesh.F);
    return *index;
  }

  /// Exact closest point (AABB tree). `hint`: a face near the answer (the vertex's last closest face), whose closest
  /// point starts the search with a small radius instead of the tree's own first guess.
  Closest global(const Eigen::Vector3d& p, int hint = -1) {
    if (hint < 0) return onFace(tree().closest(p).face, p);
    const Closest start = local(p, hint);
    core::MeshHit near;
    near.face = start.face;
    near.point = start.point;
    const int f = tree().closest(p, near).face;
    return f == start.face ? start : onFace(f, p);
  }

  /// The closest point if it lies within `radius` of p, else (found = false) only that nothing of the collider does:
  /// the tree's search starts from a sphere of that radius around p instead of one through the walk's answer, so a
  /// vertex far from the body costs a few nodes instead of every face within its distance. Without a hint: global.
  Closest within(const Eigen::Vector3d& p, int hint, double radius, bool& found) {
    found = true;
    if (hint < 0) return global(p);
    const Closest start = local(p, hint);
    if (start.squared <= radius * radius) return global(p, start.face);
    core::MeshHit
        bound;  // a point at the radius, charged to the walk's face: the search keeps it unless a face is closer
    bound.face = start.face;
    bound.point = p + radius * (start.point - p) / std::sqrt(start.squared);
    const int f = tree().closest(p, bound).face;
    const Closest c = f == start.face ? start : onFace(f, p);
    found = c.squared < radius * radius;
    return found ? c : start;
  }

  /// Closest point found by walking from face `start`: while the closest point lies on an edge or corner of the
  /// current face, move to a face around that edge or corner that is closer. Ends at a local minimum of the distance,
  /// which is the closest point when the vertex has moved little since `start` was its closest face (a few faces per
  /// call instead of a tree descent).
  Closest local(const Eigen::Vector3d& p, int start) const {
    Closest best = onFace(start, p);
    for (int step = 0; step < 64; ++step) {
      int zeros = 0, zero = -1, corner = 0;
      for (int k = 0; k < 3; ++k) {
        if (best.bary(k) <= 1e-12) ++zeros, zero = k;
        if (best.bary(k) > best.bary(corner)) corner = k;
      }
      if (zeros == 0) break;  // inside the face: a local minimum
      Closest next = best;
      if (zeros == 1) {  // on an edge: the face across it
        const int g = across[3 * best.face + zero];
        if (g >= 0) {
          const Closest candidate = onFace(g, p);
          if (candidate.squared < next.squared) next = candidate;
        }
      } else {  // at a corner: the faces around it
        const int v = mesh.F(best.face, corner);
        for (int i = ringStart[v]; i < ringStart[v + 1]; ++i) {
          if (ringFaces[i] == best.face) continue;
          const Closest candidate = onFace(ringFaces[i], p);
          if (candidate.squared < next.squared) next = candidate;
        }
      }
      if (next.face == best.face) break;
      best = next;
    }
    return best;
  }
};

/// Checks a cloth's per-vertex collider indices: one per vertex, each -1 (none) or a collider's.
inline void checkVertexColliders(const std::vector<int>& vertexCollider, size_t colliders, int vertices) {
  PIXELCLOTH_CHECK(static_cast<int>(vertexCollider.size()) == vertices,
                   "solver: " << vertexCollider.size() << " collider indices for " << vertices << " vertices");
  for (const int c : vertexCollider)
    PIXELCLOTH_CHECK(c >= -1 && c < static_cast<int>(colliders), "solver: collider index " << c << " out of range");
}

/// Moves every collider to its new vertices (same faces, so the same vertex counts, checked).
inline void moveColliders(std::vector<ColliderState>& colliders, const std::vector<Eigen::MatrixX3d>& vertices) {
  PIXELCLOTH_CHECK(vertices.size() == colliders.size(),
                   "solver: " << vertices.size() << " collider placements for " << colliders.size() << " colliders");
  for (size_t c = 0; c < vertices.size(); ++c) {
    PIXELCLOTH_CHECK(vertices[c].rows() == colliders[c].mesh.V.rows(),
                     "solver: collider " << c << " moved with a different vertex count");
    colliders[c].mesh.V = vertices[c];
    colliders[c].moved();
  }
}

}  // namespace pixelcloth::sim::detail
