#include "pixelcloth/sim/equilibrium.h"

#include <omp.h>

#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <unordered_map>

#include "collider.h"
#include "pattern.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/geometry.h"
#include "pixelcloth/core/mesh.h"

namespace pixelcloth::sim {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Bounds of the Levenberg-Marquardt damping in EquilibriumSolver::solve, 1 / h^2 for time scales h from 1 s to 0.1 ms.
constexpr double kMinDamping = 1, kMaxDamping = 1e8;
/// Cell size of the face grids (metres): a few body triangles across.
constexpr double kGridCell = 0.015;
/// EquilibriumSolver::beginStep moves vertices out of their collider from at most this deep (metres). Where an arm
/// turns, a sleeve vertex embedded on the torso rides with the torso and can end up 1.5 cm inside the arm; at 1 cm, 7
/// of the bench's 8 T-shirt poses kept such a vertex inside (the barrier, on the unsigned distance, holds it there).
constexpr double kDeepest = 0.05;
/// EquilibriumSolver::Impl::outOfFold tests this many faces nearest to an enclosed vertex for a way out.
constexpr size_t kExitsTried = 200;

/// IPC's barrier b(d) = -(d - dhat)^2 ln(d / dhat) on 0 < d < dhat and its first two derivatives.
struct Barrier {
  double value = 0, first = 0, second = 0;
};
Barrier barrier(double d, double dhat) {
  Barrier b;
  if (d >= dhat) return b;
  const double gap = d - dhat, log = std::log(d / dhat);
  b.value = -gap * gap * log;
  b.first = -2 * gap * log - gap * gap / d;
  b.second = -2 * log - 4 * gap / d + gap * gap / (d * d);
  return b;
}

/// An orthonormal basis (3 x 2) of the plane normal to the unit vector n.
Eigen::Matrix<double, 3, 2> tangentPlane(const Eigen::Vector3d& n) {
  const Eigen::Vector3d a = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  Eigen::Matrix<double, 3, 2> T;
  T.col(0) = (a - a.dot(n) * n).normalized();
  T.col(1) = n.cross(T.col(0));
  return T;
}

/// The singular value decomposition F = U diag(sigma) V^T of a triangle's 3 x 2 deformation gradient, in closed form
/// from the 2 x 2 eigenproblem of F^T F, with the triangle's normal n = u1 x u2 (the third column of a full U).
struct Polar {
  Eigen::Vector3d u1, u2, n;
  Eigen::Vector2d v1, v2;
  double s1 = 1, s2 = 1;
  explicit Polar(const Eigen::Matrix<double, 3, 2>& F) {
    const Eigen::Matrix2d C = F.transpose() * F;
    const double mean = 0.5 * (C(0, 0) + C(1, 1)), half = 0.5 * (C(0, 0) - C(1, 1));
    const double radius = std::hypot(half, C(0, 1));
    const double angle = radius > 1e-300 ? 0.5 * std::atan2(C(0, 1), half) : 0.0;
    v1 << std::cos(angle), std::sin(angle);
    v2 << -v1(1), v1(0);
    s1 = std::sqrt(std::max(mean + radius, 0.0));
    s2 = std::sqrt(std::max(mean - radius, 0.0));
    u1 = s1 > 1e-12 ? Eigen::Vector3d(F * v1 / s1) : Eigen::Vector3d::UnitX();
    u2 = F * v2;
    u2 -= u2.dot(u1) * u1;
    if (u2.norm() <= 1e-9 * std::max(s1, 1e-12)) {  // collapsed to a segment: any direction normal to u1
      const Eigen::Vector3d a = std::abs(u1.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
      u2 = a - a.dot(u1) * u1;
    }
    u2.normalize();
    n = u1.cross(u2);
  }
};

/// The quadratic bending matrix Q (n x n) of Bergou et al. (2006), one hinge per interior edge, with the flat
/// pattern as rest state: E = 1/2 sum over coordinates of x^T Q x. A hinge of edge (a, b) between triangles (a, b, c)
/// and (b, a, d) contributes 3 / (A0 + A1) k k^T, where k weighs (a, b, c, d) so that it vanishes on every affine
/// function of the hinge unfolded into the plane (each triangle in its own pattern piece, so seams bend freely from
/// flat too) and k_c = |e| / h_c, k_d = |e| / h_d with h the heights over the edge, as the cotangent weights give.
/// Its pattern touches only the hinge's four vertices, where the squared Laplacian reaches the whole 2-ring: six
/// times less fill in the Newton system's Cholesky factor.
Eigen::SparseMatrix<double> hingeBending(const core::Mesh& cloth) {
  const int n = cloth.numVertices(), m = cloth.numFaces();
  struct Side {
    int face, corner;  ///< the face and the corner of the edge's first vertex in it
  };
  std::map<std::pair<int, int>, std::vector<Side>> edges;
  for (int f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = cloth.F(f, k), b = cloth.F(f, (k + 1) % 3);
      edges[{std::min(a, b), std::max(a, b)}].push_back({f, k});
    }
  auto uv = [&](int f, int k) -> Eigen::Vector2d { return cloth.UV.row(cloth.FUV(f, k % 3)).transpose(); };
  std::vector<Eigen::Triplet<double>> entries;
  for (const auto& [key, sides] : edges) {
    if (sides.size() != 2) continue;  // boundary (or non-manifold): no hinge
    const Side s0 = sides[0], s1 = sides[1];
    // In face s0 the edge runs a -> b with c after it; in s1 (opposite orientation) b -> a with d after it.
    const int a = cloth.F(s0.face, s0.corner), b = cloth.F(s0.face, (s0.corner + 1) % 3);
    const int c = cloth.F(s0.face, (s0.corner + 2) % 3), d = cloth.F(s1.face, (s1.corner + 2) % 3);
    const Eigen::Vector2d a0 = uv(s0.face, s0.corner), b0 = uv(s0.face, s0.corner + 1), c0 = uv(s0.face, s0.corner + 2);
    const int aIn1 = cloth.F(s1.face, s1.corner) == a ? s1.corner : (s1.corner + 1) % 3;
    const Eigen::Vector2d a1 = uv(s1.face, aIn1), b1 = uv(s1.face, aIn1 == s1.corner ? s1.corner + 1 : s1.corner),
                          d1 = uv(s1.face, s1.corner + 2);
    const double length = (b0 - a0).norm(), length1 = (b1 - a1).norm();
    if (length <= 0 || length1 <= 0) continue;
    auto cross = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) { return p.x() * q.y() - p.y() * q.x(); };
    // Coordinates along the edge and heights off it, each triangle in its own piece (unfolded across a seam).
    const Eigen::Vector2d along0 = (b0 - a0) / length, along1 = (b1 - a1) / length1;
    const double xc = (c0 - a0).dot(along0), hc = std::abs(cross(along0, c0 - a0));
    const double xd = (d1 - a1).dot(along1) * length / length1, hd = std::abs(cross(along1, d1 - a1));
    if (hc <= 1e-12 || hd <= 1e-12) continue;
    Eigen::Vector4d k;
    k(2) = length / hc;
    k(3) = length / hd;
    k(1) = -(xc * k(2) + xd * k(3)) / length;
    k(0) = -(k(1) + k(2) + k(3));
    const double areas = 0.5 * length * hc + 0.5 * length1 * hd;
    const Eigen::Matrix4d Q = 3.0 / areas * k * k.transpose();
    const int ids[4] = {a, b, c, d};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) entries.emplace_back(ids[i], ids[j], Q(i, j));
  }
  Eigen::SparseMatrix<double> Q(n, n);
  Q.setFromTriplets(entries.begin(), entries.end());
  return Q;
}

/// The faces of a collider binned in a uniform grid, for the faces within the barrier distance of a point: every
/// sheet of the part that is that close (both sides of a crease), where a closest point sees only one.
class FaceGrid {
 public:
  void build(const Collider& collider, double cell) {
    cell_ = cell;
    cells_.clear();
    for (int f = 0; f < collider.F.rows(); ++f) {
      Eigen::Vector3d lo = collider.V.row(collider.F(f, 0)).transpose(), hi = lo;
      for (int k = 1; k < 3; ++k) {
        lo = lo.cwiseMin(collider.V.row(collider.F(f, k)).transpose());
        hi = hi.cwiseMax(collider.V.row(collider.F(f, k)).transpose());
      }
      forCells(lo, hi, [&](std::int64_t key) { cells_[key].push_back(f); });
    }
  }
  /// Calls visit(f) for every face binned within `radius` of p's cell range (each face once per call at most).
  template <typename Visit>
  void near(const Eigen::Vector3d& p, double radius, std::vector<int>& seen, Visit&& visit) const {
    seen.clear();
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(radius);
    forCells(p - r, p + r, [&](std::int64_t key) {
      const auto found = cells_.find(key);
      if (found == cells_.end()) return;
      for (const int f : found->second)
        if (std::find(seen.begin(), seen.end(), f) == seen.end()) {
          seen.push_back(f);
          visit(f);
        }
    });
  }

 private:
  template <typename Each>
  void forCells(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Each&& each) const {
    const Eigen::Array3i a = (lo / cell_).array().floor().cast<int>(), b = (hi / cell_).array().floor().cast<int>();
    for (int i = a(0); i <= b(0); ++i)
      for (int j = a(1); j <= b(1); ++j)
        for (int k = a(2); k <= b(2); ++k)
          each((static_cast<std::int64_t>(i + (1 << 20)) << 42) | (static_cast<std::int64_t>(j + (1 << 20)) << 21) |
               static_cast<std::int64_t>(k + (1 << 20)));
  }
  double cell_ = 0.01;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

/// One contact of a cloth vertex: a face of its collider closer than the barrier distance, with the distance to the
/// face (as a whole: C1 in the vertex's position, wherever the closest point lies) and the closest point. As in IPC
/// every such face counts, so a vertex over an edge feels both faces: summing per closest feature instead (one
/// term for an edge that two faces share) makes the energy jump where the closest point moves onto the edge.
struct Feature {
  double distance;
  Eigen::Vector3d point;
  /// The face's corner sum: a face that two colliders share (body parts overlap) counts once.
  Eigen::Vector3d corners;
  /// The Hessian of the distance: 0 over the face's interior, (I - n n^T - t t^T) / d over an edge of direction t,
  /// (I - n n^T) / d over a corner.
  Eigen::Matrix3d curvature;
};

}  // namespace

void EquilibriumOptions::validate() const {
  PIXELCLOTH_CHECK(stretchStiffness > 0 && std::isfinite(stretchStiffness),
                   "solver: stretch stiffness must be positive, got " << stretchStiffness);
  PIXELCLOTH_CHECK(compressionRatio > 0 && compressionRatio <= 1,
                   "solver: compression ratio must be in (0, 1], got " << compressionRatio);
  PIXELCLOTH_CHECK(bendStiffness >= 0 && std::isfinite(bendStiffness),
                   "solver: bend stiffness must be >= 0, got " << bendStiffness);
  PIXELCLOTH_CHECK(density > 0 && std::isfinite(density), "solver: density must be positive, got " << density);
  PIXELCLOTH_CHECK(std::isfinite(gravity), "solver: gravity must be finite");
  PIXELCLOTH_CHECK(pinStiffness > 0 && std::isfinite(pinStiffness),
                   "solver: pin stiffness must be positive, got " << pinStiffness);
  PIXELCLOTH_CHECK(barrierDistance > 0 && barrierDistance < 0.1,
                   "solver: barrier distance must be in (0, 0.1) m, got " << barrierDistance);
  PIXELCLOTH_CHECK(barrierStiffness > 0 && std::isfinite(barrierStiffness),
                   "solver: barrier stiffness must be positive, got " << barrierStiffness);
  PIXELCLOTH_CHECK(friction >= 0 && std::isfinite(friction), "solver: friction must be >= 0, got " << friction);
  PIXELCLOTH_CHECK(frictionSlip > 0 && std::isfinite(frictionSlip),
                   "solver: friction slip must be positive, got " << frictionSlip);
  PIXELCLOTH_CHECK(forceTolerance > 0, "solver: force tolerance must be positive, got " << forceTolerance);
  PIXELCLOTH_CHECK(maxMove > 0 && std::isfinite(maxMove), "solver: max move must be positive, got " << maxMove);
  PIXELCLOTH_CHECK(stepExpansions >= 0 && stepExpansions <= 10,
                   "solver: step expansions must be in [0, 10], got " << stepExpansions);
}

namespace {
/// CHOLMOD 5's supernodal factorisation opens OpenMP teams of a fixed 4 threads (CHOLMOD_OMP_NUM_THREADS, whatever
/// OMP_NUM_THREADS says); on 2 cores they wait on each other (the 1000-vertex T-shirt's Newton test: 16.4 s, against
/// 6.5 s with at most 2 threads). Dynamic adjustment, a setting of the calling thread only, lets the OpenMP runtime
/// give such a team no more threads than there are idle cores, for the duration of a solve. The dense blocks go to
/// the BLAS (OpenBLAS, OpenMP build), whose threaded Cholesky hands its parts to a team and waits for all of them to
/// run at once: a team cut short by the dynamic adjustment (one thread when the machine is busy) leaves it spinning
/// for good. So the BLAS is held to one thread for the solve too (OpenBLAS sizes its teams by the calling thread's
/// omp_get_max_threads()); the simulation's own threads are what use the cores.
class DynamicTeams {
 public:
  DynamicTeams() : dynamic_(omp_get_dynamic()), threads_(omp_get_max_threads()) {
    omp_set_dynamic(1);
    omp_set_num_threads(1);
  }
  ~DynamicTeams() {
    omp_set_num_threads(threads_);
    omp_set_dynamic(dynamic_);
  }
  DynamicTeams(const DynamicTeams&) = delete;
  DynamicTeams& operator=(const DynamicTeams&) = delete;

 private:
  int dynamic_, threads_;
};
}  // namespace

struct EquilibriumSolver::Impl {
  const EquilibriumOptions* options = nullptr;
  int n = 0;
  Eigen::MatrixX3i F;
  std::vector<Eigen::Matrix<double, 2, 3>> G;  ///< per face: F^T = G * [x0; x1; x2]
  Eigen::VectorXd restArea, mass, weight, kappa;
  Eigen::SparseMatrix<double> bending;  ///< k_b Q (n x n)
  std::vector<int> pinned;
  Eigen::MatrixX3d pinTargets;
  double friction = 0;

  std::vector<detail::ColliderState> colliders;
  std::vector<FaceGrid> grids;  ///< per collider
  std::vector<int> vertexCollider;
  /// Contact pairs: the colliders vertex v keeps off are pairCollider[pairStart[v] .. pairStart[v + 1]), its own
  /// first, then those its own meets (setColliders).
  std::vector<int> pairStart, pairCollider;
  std::vector<Feature> features;  ///< scratch: the contacts of one vertex
  std::vector<int> seenFaces;     ///< scratch
  /// Contact cache, per pair: where the vertex was last looked up, its (unsigned) distance then, and the closest
  /// point. A vertex that has moved less than that distance minus the barrier distance since is still out of the
  /// barrier's reach (the distance to a fixed surface changes no faster than the vertex moves).
  Eigen::MatrixX3d lookedAt;
  Eigen::VectorXd lookedDistance;
  std::vector<detail::Closest> closest;
  /// Per pair, a lower bound of the distance at the last accepted iterate: a trial move shorter than this cannot
  /// cross that collider's surface.
  Eigen::VectorXd startDistance;
  /// Per pair other than a vertex's own: set for the step when the vertex starts it inside that collider (the body
  /// carried it there: an arm pressed into the chest leaves no room outside both), which then neither pushes it
  /// nor stops it; its own collider always does.
  std::vector<char> dormant;

  /// Lagged friction, per vertex: mu times the normal force (0: none), the tangent plane and the step's start point.
  Eigen::VectorXd frictionForce;
  std::vector<Eigen::Matrix<double, 3, 2>> tangent;
  Eigen::MatrixX3d slideFrom;

  /// The Hessian's pattern (lower triangle of the 3n x 3n matrix), its constant part, and where each term goes.
  Eigen::SparseMatrix<double> H;
  Eigen::VectorXd constantValues;
  std::vector<int> faceSlots;    ///< per face, 81 entries (9 x 9 local, row-major): value index or -1 (upper)
  std::vector<int> vertexSlots;  ///< per vertex, 9 entries of its 3 x 3 block: value index or -1 (upper)
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  bool analysed = false;

  int slot(int row, int col) const {
    const int* begin = H.innerIndexPtr() + H.outerIndexPtr()[col];
    const int* end = H.innerIndexPtr() + H.outerIndexPtr()[col + 1];
    const int* found = std::lower_bound(begin, end, row);
    PIXELCLOTH_ASSERT(found != end && *found == row, "solver: Hessian entry (" << row << ", " << col << ") missing");
    return static_cast<int>(found - H.innerIndexPtr());
  }

  void forgetContacts() {
    lookedDistance.setConstant(-kInfinity);  // unknown: look up on first use
  }

  /// Distance of a vertex at p to the surface of pair k's collider (unsigned), from the cache when that proves the
  /// vertex out of the barrier's reach (then only a lower bound above the barrier distance), else by an exact query.
  double distance(int k, const Eigen::Vector3d& p) {
    const double moved = (p - lookedAt.row(k).transpose()).norm();
    if (lookedDistance(k) - moved > options->barrierDistance) return lookedDistance(k) - moved;
    closest[k] = colliders[pairCollider[k]].global(p, closest[k].face);
    lookedAt.row(k) = p.transpose();
    lookedDistance(k) = std::sqrt(closest[k].squared);
    return lookedDistance(k);
  }

  /// Appends to `features` the faces of collider c within the barrier distance of p.
  void gatherFeatures(int c, const Eigen::Vector3d& p) {
    const Collider& mesh = colliders[c].mesh;
    const double dhat = options->barrierDistance;
    grids[c].near(p, dhat, seenFaces, [&](int f) {
      const int ids[3] = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
      const Eigen::Vector3d a = mesh.V.row(ids[0]), b = mesh.V.row(ids[1]), d = mesh.V.row(ids[2]);
      const Eigen::Vector3d bary = core::closestPointOnTriangle(p, a, b, d);
      const Eigen::Vector3d q = bary(0) * a + bary(1) * b + bary(2) * d;
      const double distance = (p - q).norm();
      if (distance >= dhat) return;
      const Eigen::Vector3d corners = a + b + d;
      for (const Feature& seen : features)
        if (seen.distance == distance && seen.corners == corners) return;
      Eigen::Matrix3d curvature = Eigen::Matrix3d::Zero();
      int zeros = 0, zero = 0;
      for (int k = 0; k < 3; ++k)
        if (bary(k) <= 1e-12) ++zeros, zero = k;
      if (zeros > 0 && distance > 0) {
        const Eigen::Vector3d normal = (p - q) / distance;
        curvature = (Eigen::Matrix3d::Identity() - normal * normal.transpose()) / distance;
        if (zeros == 1) {
          const Eigen::Vector3d t =
              (mesh.V.row(ids[(zero + 2) % 3]) - mesh.V.row(ids[(zero + 1) % 3])).transpose().normalized();
          curvature -= t * t.transpose() / distance;
        }
      }
      features.push_back({distance, q, corners, curvature});
    });
  }

  /// The signed distance to pair k's collider (negative inside, by the pseudo-normal test), exact, and its closest
  /// point.
  double signedDistance(int k, const Eigen::Vector3d& p) {
    closest[k] = colliders[pairCollider[k]].global(p, closest[k].face);
    lookedAt.row(k) = p.transpose();
    lookedDistance(k) = std::sqrt(closest[k].squared);
    return closest[k].distance;
  }

  /// Energy at x (gravity measured from heights `reference`, a vector of n, or from 0 when null); optionally its
  /// gradient (n x 3) and the Hessian's values in H (projected to positive semi-definite per term). With `from`
  /// (the accepted iterate a trial x moves from), +infinity when a vertex's move crosses its collider's surface or
  /// touches it (gradient and Hessian then unset); without, x becomes the accepted iterate.
  double evaluate(const Eigen::MatrixX3d& x, const Eigen::VectorXd* reference, Eigen::MatrixX3d* gradient, bool hessian,
                  const Eigen::MatrixX3d* from = nullptr) {
    const EquilibriumOptions& o = *options;
    double energy = 0;
    // Contact first: an infeasible point ends the evaluation.
    const double dhat = o.barrierDistance;
    if (gradient) gradient->setZero(n, 3);
    if (hessian) std::copy(constantValues.data(), constantValues.data() + constantValues.size(), H.valuePtr());
    double* values = H.valuePtr();
    if (!colliders.empty()) {
      for (int v = 0; v < n; ++v) {
        const Eigen::Vector3d p = x.row(v).transpose();
        features.clear();
        for (int k = pairStart[v]; k < pairStart[v + 1]; ++k) {
          if (dormant[k]) continue;
          const double d = distance(k, p);
          if (from) {
            // A move shorter than the vertex's distance at the iterate cannot reach the surface; a longer one is
            // tested against the collider's triangles (continuous collision detection along the segment).
            const Eigen::Vector3d q = from->row(v).transpose();
            if (d <= 0 || ((p - q).norm() >= startDistance(k) && colliders[pairCollider[k]].tree().intersects(q, p)))
              return kInfinity;
          } else {
            if (d <= 0) return kInfinity;
            startDistance(k) = d;
          }
          if (d < dhat) gatherFeatures(pairCollider[k], p);
        }
        if (features.empty()) continue;
        Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
        for (const Feature& feature : features) {
          if (feature.distance <= 0) return kInfinity;
          const Barrier b = barrier(feature.distance, dhat);
          energy += kappa(v) * b.value;
          const Eigen::Vector3d normal = (p - feature.point) / feature.distance;
          if (gradient) gradient->row(v) += kappa(v) * b.first * normal.transpose();
          if (hessian) block += kappa(v) * (b.second * normal * normal.transpose() + b.first * feature.curvature);
        }
        if (hessian) {
          // The faces' curvature terms (b' < 0 over edges and corners) make the block indefinite: project it.
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
          eigen.computeDirect(block);
          block =
              eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
          for (int k = 0; k < 9; ++k)
            if (vertexSlots[9 * v + k] >= 0) values[vertexSlots[9 * v + k]] += block(k / 3, k % 3);
        }
      }
    }
    // Lagged friction (IPC's f0 mollifier).
    const double eps = o.frictionSlip;
    for (int v = 0; v < n; ++v) {
      if (frictionForce(v) <= 0) continue;
      const Eigen::Vector2d u = tangent[v].transpose() * (x.row(v) - slideFrom.row(v)).transpose();
      const double y = u.norm(), f = frictionForce(v);
      energy += f * (y < eps ? -y * y * y / (3 * eps * eps) + y * y / eps + eps / 3 : y);
      const double f1OverY = y < eps ? 2 / eps - y / (eps * eps) : 1 / y;
      if (gradient) gradient->row(v) += f * f1OverY * (tangent[v] * u).transpose();
      if (hessian) {
        Eigen::Matrix2d local = f * f1OverY * Eigen::Matrix2d::Identity();
        if (y > 0) {
          const Eigen::Vector2d dir = u / y;
          local -= f * (y < eps ? y / (eps * eps) : 1 / y) * dir * dir.transpose();
        }
        const Eigen::Matrix3d block = tangent[v] * local * tangent[v].transpose();
        for (int k = 0; k < 9; ++k)
          if (vertexSlots[9 * v + k] >= 0) values[vertexSlots[9 * v + k]] += block(k / 3, k % 3);
      }
    }
    // Gravity and pins.
    for (int v = 0; v < n; ++v) energy += o.gravity * mass(v) * (x(v, 1) - (reference ? (*reference)(v) : 0.0));
    if (gradient) gradient->col(1) += o.gravity * mass;
    for (size_t k = 0; k < pinned.size(); ++k) {
      const Eigen::RowVector3d gap = x.row(pinned[k]) - pinTargets.row(static_cast<int>(k));
      energy += 0.5 * o.pinStiffness * gap.squaredNorm();
      if (gradient) gradient->row(pinned[k]) += o.pinStiffness * gap;
    }
    // Bending (quadratic, constant Hessian).
    const Eigen::MatrixX3d bent = bending * x;
    energy += 0.5 * (x.array() * bent.array()).sum();
    if (gradient) *gradient += bent;
    // Stretch: 1/2 k A sum_i w_i (s_i - 1)^2 over the singular values s_i of the deformation gradient, w_i = 1 in
    // tension and the compression ratio below 1 (1: as-rigid-as-possible, |F - R|^2). With psi_i = w_i (s_i - 1),
    // the Hessian's eigensystem (Smith et al. 2019, for a 3 x 2 F) is w_i on u_i v_i^T, (psi_1 - psi_2) / (s_1 -
    // s_2) on the in-plane flip, (psi_1 + psi_2) / (s_1 + s_2) on the twist and psi_i / s_i on the out-of-plane
    // directions n v_i^T; the constant part k A G^T G holds 1 on all six, and each face corrects it by (1 - l) for
    // its eigenvalues l clamped at 0 (projected Newton).
    const double soft = o.compressionRatio;
    Eigen::Matrix3d corners;
    Eigen::Matrix<double, 9, 9> correction;
    for (int f = 0; f < F.rows(); ++f) {
      for (int k = 0; k < 3; ++k) corners.row(k) = x.row(F(f, k));
      const Eigen::Matrix<double, 3, 2> Fd = (G[f] * corners).transpose();
      const Polar polar(Fd);
      const double ka = o.stretchStiffness * restArea(f);
      const double w1 = polar.s1 >= 1 ? 1.0 : soft, w2 = polar.s2 >= 1 ? 1.0 : soft;
      const double psi1 = w1 * (polar.s1 - 1), psi2 = w2 * (polar.s2 - 1);
      energy += 0.5 * ka * (psi1 * (polar.s1 - 1) + psi2 * (polar.s2 - 1));
      if (gradient) {
        const Eigen::Matrix<double, 3, 2> P =
            psi1 * polar.u1 * polar.v1.transpose() + psi2 * polar.u2 * polar.v2.transpose();
        const Eigen::Matrix3d force = ka * P * G[f];  // column k: vertex k
        for (int k = 0; k < 3; ++k) gradient->row(F(f, k)) += force.col(k).transpose();
      }
      if (!hessian) continue;
      const double gap = polar.s1 - polar.s2, sum = polar.s1 + polar.s2;
      const double eigen[6] = {w1,
                               w2,
                               std::abs(gap) > 1e-9 ? (psi1 - psi2) / gap : w1,
                               sum > 1e-12 ? (psi1 + psi2) / sum : 0.0,
                               polar.s1 > 1e-12 ? psi1 / polar.s1 : 0.0,
                               polar.s2 > 1e-12 ? psi2 / polar.s2 : 0.0};
      const Eigen::Matrix<double, 3, 2> directions[6] = {
          polar.u1 * polar.v1.transpose(),
          polar.u2 * polar.v2.transpose(),
          (polar.u1 * polar.v2.transpose() + polar.u2 * polar.v1.transpose()) / std::sqrt(2.0),
          (polar.u1 * polar.v2.transpose() - polar.u2 * polar.v1.transpose()) / std::sqrt(2.0),
          polar.n * polar.v1.transpose(),
          polar.n * polar.v2.transpose()};
      correction.setZero();
      for (int e = 0; e < 6; ++e) {
        const double c = ka * (1 - std::max(0.0, eigen[e]));
        if (c == 0) continue;
        const Eigen::Matrix3d D = directions[e] * G[f];
        const Eigen::Map<const Eigen::Matrix<double, 9, 1>> d(D.data());
        correction.noalias() += c * d * d.transpose();
      }
      const int* slots = &faceSlots[81 * f];
      for (int k = 0; k < 81; ++k)
        if (slots[k] >= 0) values[slots[k]] -= correction(k / 9, k % 9);
    }
    return energy;
  }

  /// Moves every vertex closer to its collider than a quarter of the barrier distance, or inside it by less than
  /// kDeepest, out along its contact normal to half the barrier distance. Deeper vertices are left where they are
  /// (the barrier then keeps them off the surface from inside, and the sample's penetration test judges them): body
  /// parts are open where they meet, and "inside" an arm beyond its opening at the shoulder is not inside the body.
  /// A vertex inside a collider other than its own is left there, and that collider dormant for it. Then a vertex
  /// that its own collider encloses where that passes through itself is moved out of it (outOfFold).
  void pushOut(Eigen::MatrixX3d& x) {
    const double dhat = options->barrierDistance;
    for (int round = 0; round < 3; ++round) {
      bool moved = false;
      for (int v = 0; v < n; ++v)
        for (int k = pairStart[v]; k < pairStart[v + 1]; ++k) {
          if (dormant[k]) continue;
          const double d = signedDistance(k, x.row(v).transpose());
          if (k > pairStart[v] && d < 0) {
            dormant[k] = 1;
            continue;
          }
          if (d >= 0.25 * dhat || d < -kDeepest) continue;
          x.row(v) += (0.5 * dhat - d) * closest[k].normal.transpose();
          moved = true;
        }
      if (!moved) break;
    }
    for (int v = 0; v < n; ++v) outOfFold(v, x);
  }

  /// A part that passes through itself (skinning folds the forearm into the upper arm at a bent elbow) encloses
  /// cloth that its nearest sheet sees outside: the cloth the continuation carried behind the forearm's skin while it
  /// rode with the upper arm. The nearest sheet's test (pushOut's) misses it, and as the solve moves it on, the
  /// nearest sheet becomes the forearm's and it reads inside. Ray parity sees the part's whole volume: a vertex the
  /// part encloses is moved to the nearest point half the barrier distance in front of a face that the part does not
  /// enclose (out through every sheet of the fold, not into the next one).
  void outOfFold(int v, Eigen::MatrixX3d& x) {
    const int k = pairStart[v];
    if (k == pairStart[v + 1]) return;
    const int c = pairCollider[k];
    const Eigen::Vector3d p = x.row(v).transpose();
    if (lookedDistance(k) > kDeepest || !encloses(c, p)) return;
    const detail::ColliderState& part = colliders[c];
    std::vector<std::pair<double, Eigen::Vector3d>> exits;  // (distance, the point in front of the face)
    grids[c].near(p, kDeepest, seenFaces, [&](int f) {
      const detail::Closest hit = part.onFace(f, p);
      const double distance = std::sqrt(hit.squared);
      if (distance < kDeepest)
        exits.emplace_back(distance, hit.point + 0.5 * options->barrierDistance * part.normals.row(f).transpose());
    });
    std::sort(exits.begin(), exits.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (size_t i = 0; i < exits.size() && i < kExitsTried; ++i)
      if (!encloses(c, exits[i].second)) {
        x.row(v) = exits[i].second.transpose();
        lookedDistance(k) = -kInfinity;  // look up again
        return;
      }
  }

  /// Whether collider c's surface encloses p: each of three rays from p in different directions crosses it an odd
  /// number of times. Body parts are open where they meet: a ray that leaves an enclosed point through an opening
  /// undercounts, and one from cloth just over an opening (the shirt's hem under the torso's, its collar over the
  /// neck's) enters through it and counts one. Two of three rays let such hem and collar vertices through: the rest
  /// settle of the T-shirt took 381 Newton iterations instead of 131.
  bool encloses(int c, const Eigen::Vector3d& p) {
    const core::MeshIndex& tree = colliders[c].tree();
    return tree.crossings(p, Eigen::Vector3d(0.36, 0.48, 0.8)) % 2 == 1 &&
           tree.crossings(p, Eigen::Vector3d(-0.64, -0.6, -0.48)) % 2 == 1 &&
           tree.crossings(p, Eigen::Vector3d(0.6, -0.64, 0.48)) % 2 == 1;
  }

  /// The barrier's force on vertex v at p (zero beyond its reach).
  Eigen::Vector3d barrierPush(int v, const Eigen::Vector3d& p) {
    const double dhat = options->barrierDistance;
    Eigen::Vector3d push = Eigen::Vector3d::Zero();
    features.clear();
    for (int k = pairStart[v]; k < pairStart[v + 1]; ++k) {
      if (dormant[k]) continue;
      const double d = distance(k, p);
      if (d <= 0) return push;
      if (d < dhat) gatherFeatures(pairCollider[k], p);
    }
    for (const Feature& feature : features)
      push -= kappa(v) * barrier(feature.distance, dhat).first * (p - feature.point) / feature.distance;
    return push;
  }

  /// Per vertex, how much its lagged friction force at x exceeds mu times the normal force the barrier exerts there
  /// now (newtons, >= 0): friction lagged from a contact that has since let go or pressed less.
  Eigen::VectorXd coulombExcess(const Eigen::MatrixX3d& x) {
    Eigen::VectorXd excess = Eigen::VectorXd::Zero(n);
    const double eps = options->frictionSlip;
    for (int v = 0; v < n; ++v) {
      if (frictionForce(v) <= 0) continue;
      const Eigen::Vector2d u = tangent[v].transpose() * (x.row(v) - slideFrom.row(v)).transpose();
      const double y = u.norm();
      const double magnitude = frictionForce(v) * (y < eps ? 2 * y / eps - y * y / (eps * eps) : 1.0);
      const double allowed = friction * barrierPush(v, x.row(v).transpose()).norm();
      excess(v) = std::max(0.0, magnitude - allowed);
    }
    return excess;
  }

  /// Lags friction again at x without letting any contact's friction grow: each vertex keeps the smaller of its
  /// lagged friction force and `ease` times the Coulomb bound at x, with the tangent plane at x (zero where the
  /// contact let go). The lagged forces only fall, so the lags end, and at their end no friction exceeds mu times
  /// the normal force that holds it: a Coulomb-admissible equilibrium.
  void easeFriction(const Eigen::MatrixX3d& x, double ease) {
    for (int v = 0; v < n; ++v) {
      if (frictionForce(v) <= 0) continue;
      const Eigen::Vector3d push = barrierPush(v, x.row(v).transpose());
      const double normal = push.norm();
      frictionForce(v) = std::min(frictionForce(v), ease * friction * normal);
      if (normal > 0) tangent[v] = tangentPlane(push / normal);
    }
  }

  void lagFriction(const Eigen::MatrixX3d& x) {
    frictionForce.setZero(n);
    if (friction <= 0 || colliders.empty()) return;
    for (int v = 0; v < n; ++v) {
      const Eigen::Vector3d push = barrierPush(v, x.row(v).transpose());
      const double normal = push.norm();
      if (normal <= 0) continue;
      frictionForce(v) = friction * normal;
      tangent[v] = tangentPlane(push / normal);
    }
  }
};

EquilibriumSolver::EquilibriumSolver(const core::Mesh& cloth, const std::vector<int>& pinned,
                                     const EquilibriumOptions& options)
    : options_(options), impl_(std::make_unique<Impl>()) {
  options_.validate();
  const int n = cloth.numVertices(), m = cloth.numFaces();
  Impl& s = *impl_;
  s.options = &options_;
  s.n = n;
  s.F = cloth.F;
  detail::PatternTriangles pattern = detail::patternTriangles(cloth);
  s.G = std::move(pattern.G);
  s.restArea = std::move(pattern.area);
  const Eigen::VectorXd& vertexArea = pattern.vertexArea;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(45 * m + 6 * n);
  for (int f = 0; f < m; ++f) {
    const Eigen::Matrix3d block = options_.stretchStiffness * s.restArea(f) * s.G[f].transpose() * s.G[f];
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b)  // every coordinate pair of the two vertices (the corrections fill them)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const int row = 3 * cloth.F(f, a) + i, col = 3 * cloth.F(f, b) + j;
            if (row >= col) entries.emplace_back(row, col, i == j ? block(a, b) : 0.0);
          }
    }
  }
  s.mass = options_.density * vertexArea;
  s.weight = s.mass * (options_.gravity != 0 ? std::abs(options_.gravity) : 9.81);
  s.kappa = options_.barrierStiffness * vertexArea;

  // Bending: Bergou's hinges, per coordinate.
  s.bending = options_.bendStiffness * hingeBending(cloth);
  for (int col = 0; col < s.bending.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(s.bending, col); it; ++it)
      if (it.row() >= it.col())
        for (int i = 0; i < 3; ++i) entries.emplace_back(3 * it.row() + i, 3 * it.col() + i, it.value());
  for (const int p : pinned) {
    PIXELCLOTH_CHECK(p >= 0 && p < n, "solver: pinned vertex " << p << " out of range [0, " << n << ")");
    for (int i = 0; i < 3; ++i) entries.emplace_back(3 * p + i, 3 * p + i, options_.pinStiffness);
  }
  for (int v = 0; v < n; ++v)  // the diagonal blocks, for contact, friction and the damping term
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j <= i; ++j) entries.emplace_back(3 * v + i, 3 * v + j, 0.0);
  s.H.resize(3 * n, 3 * n);
  s.H.setFromTriplets(entries.begin(), entries.end());
  s.H.makeCompressed();
  s.constantValues = Eigen::Map<const Eigen::VectorXd>(s.H.valuePtr(), s.H.nonZeros());
  s.faceSlots.assign(81 * static_cast<size_t>(m), -1);
  for (int f = 0; f < m; ++f)
    for (int r = 0; r < 9; ++r)
      for (int c = 0; c < 9; ++c) {
        const int row = 3 * cloth.F(f, r / 3) + r % 3, col = 3 * cloth.F(f, c / 3) + c % 3;
        if (row >= col) s.faceSlots[81 * f + 9 * r + c] = s.slot(row, col);
      }
  s.vertexSlots.assign(9 * static_cast<size_t>(n), -1);
  for (int v = 0; v < n; ++v)
    for (int k = 0; k < 9; ++k)
      if (k / 3 >= k % 3) s.vertexSlots[9 * v + k] = s.slot(3 * v + k / 3, 3 * v + k % 3);

  s.pinned = pinned;
  s.pinTargets = Eigen::MatrixX3d::Zero(static_cast<int>(pinned.size()), 3);
  s.friction = options_.friction;
  s.vertexCollider.assign(n, -1);
  s.pairStart.assign(n + 1, 0);
  s.frictionForce = Eigen::VectorXd::Zero(n);
  s.tangent.assign(n, Eigen::Matrix<double, 3, 2>::Zero());
  s.slideFrom = Eigen::MatrixX3d::Zero(n, 3);
}

EquilibriumSolver::~EquilibriumSolver() = default;
EquilibriumSolver::EquilibriumSolver(EquilibriumSolver&&) noexcept = default;

int EquilibriumSolver::numVertices() const { return impl_->n; }
const Eigen::VectorXd& EquilibriumSolver::weights() const { return impl_->weight; }

void EquilibriumSolver::setColliders(std::vector<Collider> colliders, std::vector<int> vertexCollider,
                                     const std::vector<std::vector<int>>& meets) {
  detail::checkVertexColliders(vertexCollider, colliders.size(), numVertices());
  const int count = static_cast<int>(colliders.size());
  PIXELCLOTH_CHECK(meets.empty() || static_cast<int>(meets.size()) == count,
                   "solver: " << meets.size() << " lists of colliders that meet, for " << count << " colliders");
  for (int c = 0; c < static_cast<int>(meets.size()); ++c)
    for (const int other : meets[c])
      PIXELCLOTH_CHECK(other >= 0 && other < count && other != c, "solver: collider "
                                                                      << c << " meets collider " << other
                                                                      << ", expected another of 0.." << count - 1);
  Impl& s = *impl_;
  s.colliders.clear();
  s.grids.assign(colliders.size(), FaceGrid{});
  for (size_t c = 0; c < colliders.size(); ++c) s.grids[c].build(colliders[c], kGridCell);
  for (Collider& collider : colliders) s.colliders.emplace_back(std::move(collider));
  s.vertexCollider = std::move(vertexCollider);
  s.pairStart.assign(numVertices() + 1, 0);
  s.pairCollider.clear();
  for (int v = 0; v < numVertices(); ++v) {
    const int c = s.vertexCollider[v];
    if (c >= 0) {
      s.pairCollider.push_back(c);
      if (!meets.empty()) s.pairCollider.insert(s.pairCollider.end(), meets[c].begin(), meets[c].end());
    }
    s.pairStart[v + 1] = static_cast<int>(s.pairCollider.size());
  }
  const int pairs = static_cast<int>(s.pairCollider.size());
  s.lookedAt = Eigen::MatrixX3d::Zero(pairs, 3);
  s.lookedDistance.resize(pairs);
  s.startDistance = Eigen::VectorXd::Zero(pairs);
  s.closest.assign(pairs, detail::Closest{});
  s.dormant.assign(pairs, 0);
  s.forgetContacts();
  impl_->frictionForce.setZero();
}

void EquilibriumSolver::moveColliders(const std::vector<Eigen::MatrixX3d>& vertices) {
  detail::moveColliders(impl_->colliders, vertices);
  for (size_t c = 0; c < vertices.size(); ++c) impl_->grids[c].build(impl_->colliders[c].mesh, kGridCell);
  impl_->forgetContacts();
}

void EquilibriumSolver::setPinTargets(const Eigen::MatrixX3d& targets) {
  PIXELCLOTH_CHECK(targets.rows() == static_cast<int>(impl_->pinned.size()),
                   "solver: " << targets.rows() << " pin targets for " << impl_->pinned.size() << " pins");
  impl_->pinTargets = targets;
}

void EquilibriumSolver::setFriction(double friction) {
  PIXELCLOTH_CHECK(friction >= 0 && std::isfinite(friction), "solver: friction must be >= 0, got " << friction);
  impl_->friction = friction;
  if (friction == 0) impl_->frictionForce.setZero();
}

void EquilibriumSolver::beginStep(Eigen::MatrixX3d& x) {
  PIXELCLOTH_CHECK(x.rows() == numVertices(),
                   "solver: " << x.rows() << " positions for " << numVertices() << " cloth vertices");
  std::fill(impl_->dormant.begin(), impl_->dormant.end(), 0);
  impl_->pushOut(x);
  impl_->slideFrom = x;
  impl_->lagFriction(x);
}

void EquilibriumSolver::updateFriction(const Eigen::MatrixX3d& x, double ease) {
  PIXELCLOTH_CHECK(ease > 0 && ease <= 1, "solver: friction ease must be in (0, 1], got " << ease);
  impl_->easeFriction(x, ease);
}

EquilibriumReport EquilibriumSolver::solve(Eigen::MatrixX3d& x, int maxIterations, double forceTolerance) {
  const DynamicTeams teams;
  Impl& s = *impl_;
  const int n = numVertices();
  PIXELCLOTH_CHECK(x.rows() == n, "solver: " << x.rows() << " positions for " << n << " cloth vertices");
  const double tolerance = forceTolerance > 0 ? forceTolerance : options_.forceTolerance;
  const Eigen::VectorXd reference = x.col(1);  // gravity measured from here: small energies, little round-off
  EquilibriumReport report;
  Eigen::MatrixX3d gradient(n, 3), trialGradient(n, 3), trial(n, 3), further(n, 3);
  double energy = s.evaluate(x, &reference, &gradient, true);
  if (!std::isfinite(energy)) {
    s.pushOut(x);
    energy = s.evaluate(x, &reference, &gradient, true);
  }
  PIXELCLOTH_CHECK(std::isfinite(energy), "solver: the cloth starts inside its collider and could not be moved out");
  Eigen::VectorXd step(3 * n), rhs(3 * n);
  double damping = kMinDamping;
  for (;;) {
    const Eigen::VectorXd force = gradient.rowwise().norm();
    report.maxForce = force.maxCoeff();
    report.maxForceRatio = force.cwiseQuotient(s.weight).maxCoeff();
    if (report.maxForceRatio < tolerance) {
      report.converged = true;
      break;
    }
    if (report.iterations >= maxIterations) break;
    // Newton direction: H step = -gradient, H factored by CHOLMOD (the pattern is analysed once).
    if (!s.analysed) {
      // METIS's nested dissection: on the 3000-vertex T-shirt 23% fewer flops per factorisation than the AMD
      // ordering CHOLMOD picks by default (257 against 333 Mflop; 1.18 against 1.30 M nonzeros in L).
      cholmod_common& common = s.llt.cholmod();
      common.nmethods = 1;
      common.method[0].ordering = CHOLMOD_METIS;
      s.llt.analyzePattern(s.H);
      s.analysed = true;
    }
    // Levenberg-Marquardt damping (a proximal term m_v / h^2): large where a step had to be cut, so that cloth
    // that nothing holds yet (no stiffness across a fold, falling free) moves by damped steps while the held
    // cloth still takes Newton steps; it shrinks again as full steps are accepted.
    for (int v = 0; v < n; ++v)
      for (int i = 0; i < 3; ++i) s.H.valuePtr()[s.vertexSlots[9 * v + 4 * i]] += damping * s.mass(v);
    s.llt.factorize(s.H);
    if (s.llt.info() != Eigen::Success) {
      PIXELCLOTH_ASSERT(damping < kMaxDamping, "solver: the cloth Hessian could not be factored");
      damping = std::min(kMaxDamping, damping * 10);
      s.evaluate(x, &reference, &gradient, true);
      continue;
    }
    for (int v = 0; v < n; ++v)
      for (int i = 0; i < 3; ++i) rhs(3 * v + i) = -gradient(v, i);
    step = s.llt.solve(rhs);
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> move(step.data(), n, 3);
    const double longest = move.rowwise().norm().maxCoeff();
    const double slope = -step.dot(rhs);
    if (!std::isfinite(longest) || slope >= 0) {
      report.stalled = true;
      break;
    }
    // Backtracking line search on the energy (Armijo), infinite inside a collider.
    double alpha = std::min(1.0, options_.maxMove / longest);
    bool accepted = false;
    double trialEnergy = kInfinity;
    for (int halving = 0; halving < 30 && !accepted; ++halving, alpha *= 0.5) {
      trial = x + alpha * move;
      trialEnergy = s.evaluate(trial, &reference, nullptr, false, &x);
      if (trialEnergy <= energy + 1e-4 * alpha * slope) {
        accepted = true;
        break;
      }
      // Round-off: near the solution the energy change is below its own rounding error; take the step if it
      // lowers the largest net force instead.
      if (std::isfinite(trialEnergy) && std::abs(trialEnergy - energy) < 1e-12 * (1 + std::abs(energy))) {
        s.evaluate(trial, &reference, &trialGradient, false, &x);
        if (trialGradient.rowwise().norm().maxCoeff() < report.maxForce) {
          accepted = true;
          break;
        }
      }
    }
    const bool full = accepted && alpha == 1.0;
    if (full) {
      // Longer steps along the same direction while the energy keeps falling (EquilibriumOptions::stepExpansions).
      for (int expansion = 0; expansion < options_.stepExpansions && 2 * alpha * longest <= options_.maxMove;
           ++expansion) {
        further = x + 2 * alpha * move;
        const double furtherEnergy = s.evaluate(further, &reference, nullptr, false, &x);
        if (!(furtherEnergy < trialEnergy)) break;
        alpha *= 2;
        trialEnergy = furtherEnergy;
        trial.swap(further);
      }
    }
    ++report.iterations;
    damping = full ? std::max(kMinDamping, damping / 3) : std::min(kMaxDamping, damping * 10);
    if (!accepted && damping < kMaxDamping) {  // try again, more damped
      energy = s.evaluate(x, &reference, &gradient, true);
      continue;
    }
    if (!accepted) {
      report.stalled = true;
      break;
    }
    report.lastMove = alpha * longest;
    x.swap(trial);
    energy = s.evaluate(x, &reference, &gradient, true);
  }
  return report;
}

Eigen::MatrixX3d EquilibriumSolver::forces(const Eigen::MatrixX3d& x) const {
  PIXELCLOTH_CHECK(x.rows() == numVertices(),
                   "solver: " << x.rows() << " positions for " << numVertices() << " cloth vertices");
  Eigen::MatrixX3d gradient;
  const double e = impl_->evaluate(x, nullptr, &gradient, false);
  if (!std::isfinite(e)) return Eigen::MatrixX3d::Constant(x.rows(), 3, kInfinity);
  return -gradient;
}

Eigen::VectorXd EquilibriumSolver::coulombExcess(const Eigen::MatrixX3d& x) const {
  PIXELCLOTH_CHECK(x.rows() == numVertices(),
                   "solver: " << x.rows() << " positions for " << numVertices() << " cloth vertices");
  return impl_->coulombExcess(x);
}

Eigen::VectorXd EquilibriumSolver::distances(const Eigen::MatrixX3d& x) const {
  Impl& s = *impl_;
  Eigen::VectorXd d = Eigen::VectorXd::Constant(x.rows(), kInfinity);
  for (int v = 0; v < x.rows() && v < s.n; ++v) {
    const int c = s.vertexCollider[v];
    if (c >= 0) d(v) = s.colliders[c].global(x.row(v).transpose(), s.closest[s.pairStart[v]].face).distance;
  }
  return d;
}

void EquilibriumSolver::closestPoints(const Eigen::MatrixX3d& x, Eigen::VectorXi& face,
                                      Eigen::MatrixX3d& barycentric) const {
  PIXELCLOTH_CHECK(x.rows() == numVertices(),
                   "solver: " << x.rows() << " positions for " << numVertices() << " cloth vertices");
  Impl& s = *impl_;
  face = Eigen::VectorXi::Constant(s.n, -1);
  barycentric = Eigen::MatrixX3d::Zero(s.n, 3);
  for (int v = 0; v < s.n; ++v) {
    const int c = s.vertexCollider[v];
    if (c < 0) continue;
    // No hint: where two faces are equally close the tree's own choice, the same whatever was solved before.
    const detail::Closest closest = s.colliders[c].global(x.row(v).transpose());
    face(v) = closest.face;
    barycentric.row(v) = closest.bary.transpose();
  }
}

Eigen::VectorXd EquilibriumSolver::clearances(const Eigen::MatrixX3d& x) const {
  Impl& s = *impl_;
  Eigen::VectorXd d = Eigen::VectorXd::Constant(x.rows(), kInfinity);
  for (int v = 0; v < x.rows() && v < s.n; ++v)
    for (int k = s.pairStart[v]; k < s.pairStart[v + 1]; ++k)
      if (!s.dormant[k])
        d(v) = std::min(
            d(v), std::sqrt(s.colliders[s.pairCollider[k]].global(x.row(v).transpose(), s.closest[k].face).squared));
  return d;
}

Eigen::VectorXd EquilibriumSolver::areaRatios(const Eigen::MatrixX3d& x) const {
  return core::triangleAreas(x, impl_->F).cwiseQuotient(impl_->restArea);
}

double EquilibriumSolver::energy(const Eigen::MatrixX3d& x) const {
  PIXELCLOTH_CHECK(x.rows() == numVertices(),
                   "solver: " << x.rows() << " positions for " << numVertices() << " cloth vertices");
  return impl_->evaluate(x, nullptr, nullptr, false);
}

}  // namespace pixelcloth::sim
