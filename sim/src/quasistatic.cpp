#include "pixelcloth/sim/quasistatic.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "collider.h"
#include "pattern.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/geometry.h"
#include "pixelcloth/core/mesh_index.h"

namespace pixelcloth::sim {

namespace {

using detail::Closest;
using detail::ColliderState;

/// Contact state of one cloth vertex.
struct Contact {
  bool active = false;
  Closest closest;    ///< the closest collider point at the last look (active: at the vertex's current position)
  double budget = 0;  ///< inactive: how far the vertex may still move before it must look again (metres)
};

/// A sparse Cholesky factor P^T L L^T P (Eigen's SimplicialLLT, AMD ordering) with a solve for three right-hand
/// sides at once: Eigen solves them one column at a time, which reads L three times per pass; here each pass reads it
/// once (about 2x faster for cloth-sized systems).
class ThreeColumnCholesky {
 public:
  /// Factors A; later calls with the same sparsity pattern reuse the ordering and symbolic analysis.
  bool compute(const Eigen::SparseMatrix<double>& A) {
    if (!analysed_) {
      llt_.analyzePattern(A);
      analysed_ = true;
    }
    llt_.factorize(A);
    if (llt_.info() != Eigen::Success) return false;
    L_ = llt_.matrixL();
    L_.makeCompressed();
    permutation_ = llt_.permutationP().indices();
    work_.resize(A.rows(), 3);
    return true;
  }
  void solve(const Eigen::MatrixX3d& b, Eigen::MatrixX3d& x) {
    const int n = static_cast<int>(L_.rows());
    const int* outer = L_.outerIndexPtr();
    const int* inner = L_.innerIndexPtr();
    const double* value = L_.valuePtr();
    for (int i = 0; i < n; ++i) work_.row(permutation_[i]) = b.row(i);
    for (int j = 0; j < n; ++j) {  // L y = P b (columns of L hold the diagonal first)
      double* yj = &work_(j, 0);
      const double d = value[outer[j]];
      yj[0] /= d, yj[1] /= d, yj[2] /= d;
      for (int p = outer[j] + 1; p < outer[j + 1]; ++p) {
        double* yi = &work_(inner[p], 0);
        yi[0] -= value[p] * yj[0], yi[1] -= value[p] * yj[1], yi[2] -= value[p] * yj[2];
      }
    }
    for (int j = n - 1; j >= 0; --j) {  // L^T z = y
      double* yj = &work_(j, 0);
      double s0 = yj[0], s1 = yj[1], s2 = yj[2];
      for (int p = outer[j] + 1; p < outer[j + 1]; ++p) {
        const double* yi = &work_(inner[p], 0);
        s0 -= value[p] * yi[0], s1 -= value[p] * yi[1], s2 -= value[p] * yi[2];
      }
      const double d = value[outer[j]];
      yj[0] = s0 / d, yj[1] = s1 / d, yj[2] = s2 / d;
    }
    x.resize(n, 3);
    for (int i = 0; i < n; ++i) x.row(i) = work_.row(permutation_[i]);
  }

 private:
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt_;
  bool analysed_ = false;
  Eigen::SparseMatrix<double> L_;
  Eigen::VectorXi permutation_;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> work_;
};

}  // namespace

void QuasistaticOptions::validate() const {
  PIXELCLOTH_CHECK(stretchStiffness > 0 && std::isfinite(stretchStiffness),
                   "solver: stretch stiffness must be positive, got " << stretchStiffness);
  PIXELCLOTH_CHECK(bendStiffness >= 0 && std::isfinite(bendStiffness),
                   "solver: bend stiffness must be >= 0, got " << bendStiffness);
  PIXELCLOTH_CHECK(density > 0 && std::isfinite(density), "solver: density must be positive, got " << density);
  PIXELCLOTH_CHECK(std::isfinite(gravity), "solver: gravity must be finite");
  PIXELCLOTH_CHECK(timeScale > 0 && std::isfinite(timeScale), "solver: time scale must be positive, got " << timeScale);
  PIXELCLOTH_CHECK(pinStiffness > 0, "solver: pin stiffness must be positive, got " << pinStiffness);
  PIXELCLOTH_CHECK(
      contactOffset >= 0 && contactActivation > contactOffset,
      "solver: need 0 <= contact offset < contact activation, got " << contactOffset << " and " << contactActivation);
  PIXELCLOTH_CHECK(maxStep > 0 && maxStep < contactActivation,
                   "solver: need 0 < max step < contact activation, got " << maxStep);
  PIXELCLOTH_CHECK(tolerance > 0, "solver: tolerance must be positive, got " << tolerance);
  PIXELCLOTH_CHECK(contactRecheckEvery >= 1,
                   "solver: contact recheck interval must be >= 1, got " << contactRecheckEvery);
  PIXELCLOTH_CHECK(friction >= 0 && std::isfinite(friction), "solver: friction must be >= 0, got " << friction);
}

struct QuasistaticSolver::Impl {
  Eigen::MatrixX3i F;
  std::vector<Eigen::Matrix<double, 2, 3>> G;  ///< per face: F^T = G * [x0; x1; x2]
  Eigen::VectorXd restArea;                    ///< per face, pattern area
  Eigen::VectorXd mass;                        ///< per vertex (kg)
  std::vector<int> pinned;
  Eigen::MatrixX3d pinTargets;
  Eigen::SparseMatrix<double> bending;  ///< k_b Q
  ThreeColumnCholesky solver;
  Eigen::SparseMatrix<double> system;  ///< without contacts (every diagonal entry stored, so contacts keep the pattern)
  Eigen::VectorXd contactWeight;       ///< per vertex: the contact stiffness in the factored system, or 0
  Eigen::MatrixX3d anchors;            ///< per vertex: where its contact spring pulls (the sticking point)
  bool springsFrozen = false;          ///< keep the factored spring set (freezeContactSprings)
  std::vector<ColliderState> colliders;
  std::vector<int> vertexCollider;
  std::vector<Contact> contacts;

  /// Looks up the contact of vertex v at `p` in its collider's tree: active when p is closer than `activation` (or
  /// inside); otherwise the vertex may travel its distance minus the activation before it needs another look.
  /// The search looks no further than 1.5 times the activation: a vertex beyond gets the budget that far allows, and
  /// looks again after it (the closest face it keeps is the walk's, a hint only).
  void queryContact(int v, const Eigen::Vector3d& p, double activation) {
    const int hint = contacts[v].closest.face;
    contacts[v] = Contact{};
    const int c = vertexCollider[v];
    if (c < 0) return;
    const double reach = 1.5 * activation;
    bool found = true;
    contacts[v].closest = colliders[c].within(p, hint, reach, found);
    contacts[v].active = found && contacts[v].closest.distance < activation;
    if (!contacts[v].active) contacts[v].budget = (found ? contacts[v].closest.distance : reach) - activation;
  }

  void queryContacts(const Eigen::MatrixX3d& x, double activation) {
    for (int v = 0; v < x.rows(); ++v) queryContact(v, x.row(v).transpose(), activation);
  }

  /// After an iteration moved the cloth from `before` to `after`: active contacts follow their vertex by a local walk
  /// from the last closest face (exact closest points every iteration, so planes never go stale where the body
  /// curves); inactive vertices spend their travel budget and look again in the tree once it is used up. A vertex with
  /// budget left before the iteration was at least `activation` away and moved at most the maximum step, so it is
  /// still outside and the fresh look cannot miss a part it tunnelled through.
  void trackContacts(const Eigen::MatrixX3d& before, const Eigen::MatrixX3d& after, double activation, bool global) {
    for (int v = 0; v < after.rows(); ++v) {
      const int c = vertexCollider[v];
      if (c < 0) continue;
      Contact& contact = contacts[v];
      const Eigen::Vector3d p = after.row(v).transpose();
      if (contact.active) {
        contact.closest =
            global ? colliders[c].global(p, contact.closest.face) : colliders[c].local(p, contact.closest.face);
        if (contact.closest.distance >= activation) {
          contact.active = false;
          contact.budget = contact.closest.distance - activation;
        }
      } else {
        contact.budget -= (after.row(v) - before.row(v)).norm();
        if (contact.budget < 0) queryContact(v, p, activation);
      }
    }
  }

  /// Contacts enter the global step as stiff springs towards their anchors, so the solve sees the body's support and
  /// friction instead of only having them restored afterwards. The springs sit on the vertices in contact when the
  /// system was last factored: it is refactored when the contact set has changed by more than 2% of the vertices
  /// (those in between rely on projection alone; springs left on vertices that lifted off only damp them), and
  /// always at the start of a `relax` call (`always`), so that a call's result does not depend on earlier calls.
  void updateContactWeights(double stiffness, bool always) {
    Eigen::VectorXd weight = Eigen::VectorXd::Zero(contactWeight.size());
    for (int v = 0; v < weight.size(); ++v)
      if (contacts[v].active) weight(v) = stiffness;
    const int changed = static_cast<int>((weight - contactWeight).cwiseAbs().cwiseSign().sum());
    if (springsFrozen) return;
    if (!always && changed <= weight.size() / 50) return;
    contactWeight = weight;
    Eigen::SparseMatrix<double> A = system;
    for (int v = 0; v < weight.size(); ++v)
      if (weight(v) > 0) A.coeffRef(v, v) += weight(v);
    PIXELCLOTH_ASSERT(solver.compute(A), "solver: the cloth system with contact springs could not be factored");
  }

  /// Coulomb friction on the contact springs, after a global step moved the cloth to `x` (before projection): the
  /// spring force k (anchor - x) splits into a normal part (the body's support, when it pushes outwards) and a
  /// tangential part (friction). While the tangential part stays within `friction` times the normal part the anchor
  /// stays (the vertex sticks); beyond, the anchor slides after the vertex until the cone is met; a vertex the spring
  /// pulls towards the body is let go. Anchors of touching vertices sit `offset` outside the body; a vertex within
  /// the activation distance but not touching is free (its anchor follows it, which only damps it).
  void updateAnchors(const Eigen::MatrixX3d& x, double friction, double offset) {
    for (int v = 0; v < x.rows(); ++v) {
      const Contact& contact = contacts[v];
      if (!contact.active || contactWeight(v) == 0) continue;
      const Eigen::Vector3d p = x.row(v).transpose(), n = contact.closest.normal;
      if (contact.closest.distance > 1.5 * offset) {  // near the body but not touching it: free (only damped)
        anchors.row(v) = p.transpose();
        continue;
      }
      const Eigen::Vector3d pull = anchors.row(v).transpose() - p;
      const double normal = pull.dot(n);
      Eigen::Vector3d anchor = p;
      if (normal > 0) {
        const Eigen::Vector3d tangential = pull - normal * n;
        const double slip = tangential.norm();
        anchor = p + normal * n + (slip > friction * normal ? friction * normal / slip : 1.0) * tangential;
      }
      anchor += (offset - (anchor - contact.closest.point).dot(n)) * n;  // on the body, `offset` outside
      anchors.row(v) = anchor.transpose();
    }
  }

  /// Moves every active contact vertex at least `offset` outside its collider, along the contact normal.
  void projectContacts(Eigen::MatrixX3d& x, double offset) const {
    for (int v = 0; v < x.rows(); ++v) {
      const Contact& contact = contacts[v];
      if (contact.active && contact.closest.distance < offset)
        x.row(v) += (offset - contact.closest.distance) * contact.closest.normal.transpose();
    }
  }
};

QuasistaticSolver::QuasistaticSolver(const core::Mesh& cloth, const std::vector<int>& pinned,
                                     const QuasistaticOptions& options)
    : options_(options), impl_(std::make_unique<Impl>()) {
  options_.validate();
  const int n = cloth.numVertices(), m = cloth.numFaces();
  Impl& s = *impl_;
  s.F = cloth.F;
  detail::PatternTriangles pattern = detail::patternTriangles(cloth);
  s.G = std::move(pattern.G);
  s.restArea = std::move(pattern.area);
  const Eigen::VectorXd& vertexArea = pattern.vertexArea;
  std::vector<Eigen::Triplet<double>> stretch;
  stretch.reserve(9 * m);
  for (int f = 0; f < m; ++f) {
    const Eigen::Matrix3d block = options_.stretchStiffness * s.restArea(f) * s.G[f].transpose() * s.G[f];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) stretch.emplace_back(cloth.F(f, a), cloth.F(f, b), block(a, b));
  }
  s.mass = options_.density * vertexArea;

  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(stretch.begin(), stretch.end());
  // Bending: the squared cotangent Laplacian of the flat pattern (its sign does not matter).
  const Eigen::SparseMatrix<double> L = core::cotangentLaplacian(cloth.UV, cloth.FUV, cloth.F, n);
  const Eigen::VectorXd inverseArea = vertexArea.cwiseInverse();
  s.bending = options_.bendStiffness * Eigen::SparseMatrix<double>(L.transpose() * inverseArea.asDiagonal() * L);

  Eigen::SparseMatrix<double> diagonal(n, n);
  std::vector<Eigen::Triplet<double>> diag;
  const double proximal = 1.0 / (options_.timeScale * options_.timeScale);
  for (int v = 0; v < n; ++v) diag.emplace_back(v, v, proximal * s.mass(v));
  for (const int p : pinned) {
    PIXELCLOTH_CHECK(p >= 0 && p < n, "solver: pinned vertex " << p << " out of range [0, " << n << ")");
    diag.emplace_back(p, p, options_.pinStiffness);
  }
  diagonal.setFromTriplets(diag.begin(), diag.end());
  s.pinned = pinned;
  s.pinTargets = Eigen::MatrixX3d::Zero(static_cast<int>(pinned.size()), 3);
  s.system = K + s.bending + diagonal;
  s.system.makeCompressed();
  s.contactWeight = Eigen::VectorXd::Zero(n);
  PIXELCLOTH_ASSERT(s.solver.compute(s.system), "solver: the cloth system could not be factored");
  s.contacts.assign(n, Contact{});
}

QuasistaticSolver::~QuasistaticSolver() = default;
QuasistaticSolver::QuasistaticSolver(QuasistaticSolver&&) noexcept = default;

int QuasistaticSolver::numVertices() const { return static_cast<int>(impl_->mass.size()); }

void QuasistaticSolver::setColliders(std::vector<Collider> colliders, std::vector<int> vertexCollider) {
  detail::checkVertexColliders(vertexCollider, colliders.size(), numVertices());
  impl_->colliders.clear();
  for (Collider& collider : colliders) impl_->colliders.emplace_back(std::move(collider));
  impl_->vertexCollider = std::move(vertexCollider);
  impl_->contacts.assign(numVertices(), Contact{});
  // New colliders, new contacts: springs frozen for the old ones no longer apply.
  impl_->springsFrozen = false;
  impl_->contactWeight.setZero();
  PIXELCLOTH_ASSERT(impl_->solver.compute(impl_->system), "solver: the cloth system could not be factored");
}

void QuasistaticSolver::moveColliders(const std::vector<Eigen::MatrixX3d>& vertices) {
  detail::moveColliders(impl_->colliders, vertices);
}

void QuasistaticSolver::freezeContactSprings(const Eigen::MatrixX3d& x) {
  Impl& s = *impl_;
  PIXELCLOTH_CHECK(!s.colliders.empty(), "solver: no colliders, so no contact springs to freeze");
  PIXELCLOTH_CHECK(x.rows() == numVertices(),
                   "solver: " << x.rows() << " positions for " << numVertices() << " cloth vertices");
  s.springsFrozen = false;
  s.queryContacts(x, options_.contactActivation);
  s.updateContactWeights(options_.contactStiffness, true);
  s.springsFrozen = true;
}

void QuasistaticSolver::setFriction(double friction) {
  PIXELCLOTH_CHECK(friction >= 0 && std::isfinite(friction), "solver: friction must be >= 0, got " << friction);
  options_.friction = friction;
}

void QuasistaticSolver::setContactRecheckEvery(int iterations) {
  PIXELCLOTH_CHECK(iterations >= 1, "solver: contact recheck interval must be >= 1, got " << iterations);
  options_.contactRecheckEvery = iterations;
}

void QuasistaticSolver::setPinTargets(const Eigen::MatrixX3d& targets) {
  PIXELCLOTH_CHECK(targets.rows() == static_cast<int>(impl_->pinned.size()),
                   "solver: " << targets.rows() << " pin targets for " << impl_->pinned.size() << " pins");
  impl_->pinTargets = targets;
}

RelaxReport QuasistaticSolver::relax(Eigen::MatrixX3d& x, int maxIterations, int minIterations) {
  Impl& s = *impl_;
  const int n = numVertices();
  PIXELCLOTH_CHECK(x.rows() == n, "solver: " << x.rows() << " positions for " << n << " cloth vertices");
  const double proximal = 1.0 / (options_.timeScale * options_.timeScale);
  Eigen::MatrixX3d constant = Eigen::MatrixX3d::Zero(n, 3);
  constant.col(1) = -options_.gravity * s.mass;
  for (size_t k = 0; k < s.pinned.size(); ++k)
    constant.row(s.pinned[k]) += options_.pinStiffness * s.pinTargets.row(static_cast<int>(k));

  RelaxReport report;
  Eigen::MatrixX3d rhs(n, 3), next(n, 3);
  Eigen::Matrix<double, 3, 3> corners;
  // Every call starts from a fresh look in the trees (the colliders or the cloth may have moved since the last one)
  // and a system factored for those contacts, with every contact sticking where its vertex is. (Carrying the last
  // call's contacts over a continuation step instead saved 5% and kept 2 fewer of 288 sampled poses.)
  if (!s.colliders.empty()) {
    s.queryContacts(x, options_.contactActivation);
    s.updateContactWeights(options_.contactStiffness, true);
  }
  s.anchors = x;
  for (int it = 0; it < maxIterations; ++it) {
    if (!s.colliders.empty() && it > 0) s.updateContactWeights(options_.contactStiffness, false);
    // Local step: nearest rotation (3x2 with orthonormal columns) to each deformation gradient; contact springs pull
    // towards their anchors.
    rhs = constant;
    rhs += proximal * s.mass.asDiagonal() * x;
    rhs += s.contactWeight.asDiagonal() * s.anchors;
    for (int f = 0; f < s.F.rows(); ++f) {
      for (int k = 0; k < 3; ++k) corners.row(k) = x.row(s.F(f, k));
      const Eigen::Matrix<double, 3, 2> Fd = (s.G[f] * corners).transpose();
      // R = F (F^T F)^(-1/2), with the closed-form square root of a 2x2 SPD matrix C:
      // sqrt(C) = (C + sqrt(det C) I) / sqrt(tr C + 2 sqrt(det C)).
      const Eigen::Matrix2d C = Fd.transpose() * Fd;
      const double det = C.determinant();
      Eigen::Matrix<double, 3, 2> R;
      if (det > 1e-12 * C.trace() * C.trace()) {
        const double root = std::sqrt(det);
        Eigen::Matrix2d S = C;
        S.diagonal().array() += root;
        S /= std::sqrt(C.trace() + 2 * root);
        R = Fd * S.inverse();
      } else {
        Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(Fd, Eigen::ComputeFullU | Eigen::ComputeFullV);
        R = svd.matrixU().leftCols<2>() * svd.matrixV().transpose();
      }
      const Eigen::Matrix3d force = options_.stretchStiffness * s.restArea(f) * s.G[f].transpose() * R.transpose();
      for (int k = 0; k < 3; ++k) rhs.row(s.F(f, k)) += force.row(k);
    }
    // Global step, then contacts.
    s.solver.solve(rhs, next);
    for (int v = 0; v < n; ++v) {  // no vertex moves further than maxStep in one iteration
      const double step = (next.row(v) - x.row(v)).norm();
      if (step > options_.maxStep) next.row(v) = x.row(v) + (options_.maxStep / step) * (next.row(v) - x.row(v));
    }
    if (!s.colliders.empty()) {
      s.trackContacts(x, next, options_.contactActivation, (it + 1) % options_.contactRecheckEvery == 0);
      s.updateAnchors(next, options_.friction, options_.contactOffset);
      s.projectContacts(next, options_.contactOffset);
      for (int v = 0; v < n; ++v)  // springs without a contact (lifted off) only damp: they follow their vertex
        if (!s.contacts[v].active || s.contactWeight(v) == 0) s.anchors.row(v) = next.row(v);
    }
    report.residual = (next - x).rowwise().norm().maxCoeff();
    x.swap(next);
    report.iterations = it + 1;
    if (!std::isfinite(report.residual)) break;
    if (report.residual < options_.tolerance && report.iterations >= minIterations) {
      report.converged = true;
      break;
    }
  }
  return report;
}

Eigen::VectorXd QuasistaticSolver::penetration(const Eigen::MatrixX3d& x) const {
  Impl& s = *impl_;
  Eigen::VectorXd depth = Eigen::VectorXd::Zero(x.rows());
  for (int v = 0; v < x.rows(); ++v) {
    const int c = v < static_cast<int>(s.vertexCollider.size()) ? s.vertexCollider[v] : -1;
    if (c < 0) continue;
    // The last closest face only seeds the search (the answer is the exact closest point either way), so the tree
    // needs no k-d tree of its own to start from.
    depth(v) = std::max(0.0, -s.colliders[c].global(x.row(v).transpose(), s.contacts[v].closest.face).distance);
  }
  return depth;
}

Eigen::VectorXd QuasistaticSolver::areaRatios(const Eigen::MatrixX3d& x) const {
  return core::triangleAreas(x, impl_->F).cwiseQuotient(impl_->restArea);
}
double QuasistaticSolver::energy(const Eigen::MatrixX3d& x) const {
  const Impl& s = *impl_;
  double e = 0;
  Eigen::Matrix3d corners;
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) corners.row(k) = x.row(s.F(f, k));
    const Eigen::Matrix<double, 3, 2> Fd = (s.G[f] * corners).transpose();
    Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(Fd);
    const Eigen::Vector2d sigma = svd.singularValues();
    e += 0.5 * options_.stretchStiffness * s.restArea(f) * (sigma - Eigen::Vector2d::Ones()).squaredNorm();
  }
  e += 0.5 * (x.transpose() * (s.bending * x)).trace();
  e += options_.gravity * s.mass.dot(x.col(1));
  for (size_t k = 0; k < s.pinned.size(); ++k)
    e += 0.5 * options_.pinStiffness * (x.row(s.pinned[k]) - s.pinTargets.row(static_cast<int>(k))).squaredNorm();
  return e;
}

}  // namespace pixelcloth::sim
