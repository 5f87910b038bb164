#include "pixelcloth/sim/quasistatic.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "pixelcloth/core/error.h"

namespace pixelcloth::sim {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Point toPoint(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
Eigen::Vector3d toEigen(const Point& p) { return {p.x(), p.y(), p.z()}; }

/// A collider with its search structure (rebuilt lazily after the vertices move).
struct ColliderState {
  Collider mesh;
  std::vector<Triangle> triangles;
  std::unique_ptr<Tree> tree;

  void rebuild() {
    triangles.resize(mesh.F.rows());
    for (int f = 0; f < mesh.F.rows(); ++f)
      triangles[f] = Triangle(toPoint(mesh.V.row(mesh.F(f, 0))), toPoint(mesh.V.row(mesh.F(f, 1))),
                              toPoint(mesh.V.row(mesh.F(f, 2))));
    tree = std::make_unique<Tree>(triangles.cbegin(), triangles.cend());
    tree->accelerate_distance_queries();
  }
  Eigen::Vector3d faceNormal(int f) const {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    return (b - a).cross(c - a).normalized();
  }
  Eigen::Vector3d pointAt(int f, const Eigen::Vector3d& bary) const {
    return bary(0) * mesh.V.row(mesh.F(f, 0)).transpose() + bary(1) * mesh.V.row(mesh.F(f, 1)).transpose() +
           bary(2) * mesh.V.row(mesh.F(f, 2)).transpose();
  }
  /// Closest face and the barycentric coordinates of the closest point on it.
  std::pair<int, Eigen::Vector3d> closest(const Eigen::Vector3d& x) {
    if (!tree) rebuild();
    const auto [point, primitive] = tree->closest_point_and_primitive(toPoint(x));
    const int f = static_cast<int>(primitive - triangles.cbegin());
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    return {f, core::barycentricCoordinates(toEigen(point), a, b, c)};
  }
};

/// Contact plane of one cloth vertex: a collider triangle and a point in it.
struct Contact {
  int face = -1;  ///< -1: inactive
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
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
  PIXELCLOTH_CHECK(contactQueryEvery >= 1, "solver: contact query interval must be >= 1");
  PIXELCLOTH_CHECK(maxStep > 0 && maxStep < contactActivation,
                   "solver: need 0 < max step < contact activation, got " << maxStep);
  PIXELCLOTH_CHECK(tolerance > 0, "solver: tolerance must be positive, got " << tolerance);
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
  std::vector<ColliderState> colliders;
  std::vector<int> vertexCollider;
  std::vector<Contact> contacts;
  int sinceQuery = 0;
  bool queryNeeded = true;

  /// Finds the contact plane of vertex v at `p`: active when p is closer than `activation` to its collider (or
  /// inside); otherwise the vertex may travel its distance minus the activation before it needs another look.
  void queryContact(int v, const Eigen::Vector3d& p, double activation) {
    contacts[v] = Contact{};
    const int c = vertexCollider[v];
    if (c < 0) return;
    auto [face, bary] = colliders[c].closest(p);
    const double signedDistance = (p - colliders[c].pointAt(face, bary)).dot(colliders[c].faceNormal(face));
    if (signedDistance < activation) {
      contacts[v] = Contact{face, bary, 0.5 * activation};
    } else {
      contacts[v].budget = signedDistance - activation;
    }
  }

  void queryContacts(const Eigen::MatrixX3d& x, double activation) {
    for (int v = 0; v < x.rows(); ++v) queryContact(v, x.row(v).transpose(), activation);
    sinceQuery = 0;
    queryNeeded = false;
  }

  /// A vertex that has used up its travel budget gets its plane looked up again, from where it was before this
  /// iteration (outside), so a fast vertex cannot tunnel through a thin part (an arm) unseen. Vertices with a plane
  /// look again once they have slid half the activation distance from where they found it.
  void refreshMovedContacts(const Eigen::MatrixX3d& before, const Eigen::MatrixX3d& after, double activation) {
    for (int v = 0; v < before.rows(); ++v) {
      Contact& contact = contacts[v];
      if (vertexCollider[v] < 0) continue;
      contact.budget -= (after.row(v) - before.row(v)).norm();
      if (contact.budget < 0) {
        queryContact(v, before.row(v).transpose(), activation);
        if (contacts[v].face >= 0) contacts[v].budget = 0.5 * activation;
      }
    }
  }

  /// Contacts enter the global step as stiff springs towards the contact plane (refactoring when the set of vertices
  /// in contact changes), so the solve sees the body's support instead of only having it restored afterwards.
  void updateContactWeights(double stiffness) {
    Eigen::VectorXd weight = Eigen::VectorXd::Zero(contactWeight.size());
    for (int v = 0; v < weight.size(); ++v)
      if (contacts[v].face >= 0) weight(v) = stiffness;
    // Refactoring costs a few milliseconds: skip it while the contact set has changed by under 2% of the vertices
    // (those still rely on projection, and springs left on vertices that lifted off only damp them).
    const int changed = static_cast<int>((weight - contactWeight).cwiseAbs().cwiseSign().sum());
    if (changed <= weight.size() / 50) return;
    contactWeight = weight;
    Eigen::SparseMatrix<double> A = system;
    for (int v = 0; v < weight.size(); ++v)
      if (weight(v) > 0) A.coeffRef(v, v) += weight(v);
    solver.compute(A);
  }

  /// Right-hand side of the contact springs: each vertex in the factored contact set is pulled to its current
  /// position moved onto the outside of its contact plane.
  void addContactTargets(const Eigen::MatrixX3d& x, double offset, Eigen::MatrixX3d& rhs) const {
    for (int v = 0; v < x.rows(); ++v) {
      if (contactWeight(v) == 0) continue;
      Eigen::Vector3d target = x.row(v).transpose();
      const Contact& contact = contacts[v];
      if (contact.face >= 0) {
        const ColliderState& collider = colliders[vertexCollider[v]];
        const Eigen::Vector3d n = collider.faceNormal(contact.face);
        const double d = (target - collider.pointAt(contact.face, contact.bary)).dot(n);
        if (d < offset) target += (offset - d) * n;
      }
      rhs.row(v) += contactWeight(v) * target.transpose();
    }
  }

  void projectContacts(Eigen::MatrixX3d& x, double offset) const {
    for (int v = 0; v < x.rows(); ++v) {
      const Contact& contact = contacts[v];
      if (contact.face < 0) continue;
      const ColliderState& collider = colliders[vertexCollider[v]];
      const Eigen::Vector3d n = collider.faceNormal(contact.face);
      const Eigen::Vector3d q = collider.pointAt(contact.face, contact.bary);
      const double d = (x.row(v).transpose() - q).dot(n);
      if (d < offset) x.row(v) += (offset - d) * n.transpose();
    }
  }
};

QuasistaticSolver::QuasistaticSolver(const core::Mesh& cloth, const std::vector<int>& pinned,
                                     const QuasistaticOptions& options)
    : options_(options), impl_(std::make_unique<Impl>()) {
  options_.validate();
  PIXELCLOTH_CHECK(cloth.hasUV(), "solver: the cloth mesh needs per-corner pattern coordinates (UV) as rest shape");
  const int n = cloth.numVertices(), m = cloth.numFaces();
  Impl& s = *impl_;
  s.F = cloth.F;
  s.G.resize(m);
  s.restArea.resize(m);
  s.mass = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd vertexArea = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::Triplet<double>> stretch, laplace;
  stretch.reserve(9 * m);
  laplace.reserve(12 * m);
  Eigen::Matrix<double, 2, 3> edges;
  edges << -1, 1, 0, -1, 0, 1;
  for (int f = 0; f < m; ++f) {
    Eigen::Vector2d u[3];
    for (int k = 0; k < 3; ++k) u[k] = cloth.UV.row(cloth.FUV(f, k)).transpose();
    Eigen::Matrix2d Dm;
    Dm.col(0) = u[1] - u[0];
    Dm.col(1) = u[2] - u[0];
    const double area = 0.5 * std::abs(Dm.determinant());
    PIXELCLOTH_CHECK(area > 1e-12, "solver: pattern triangle " << f << " is degenerate (area " << area << " m^2)");
    s.restArea(f) = area;
    s.G[f] = Dm.inverse().transpose() * edges;
    const Eigen::Matrix3d block = options_.stretchStiffness * area * s.G[f].transpose() * s.G[f];
    for (int a = 0; a < 3; ++a) {
      vertexArea(cloth.F(f, a)) += area / 3.0;
      for (int b = 0; b < 3; ++b) stretch.emplace_back(cloth.F(f, a), cloth.F(f, b), block(a, b));
    }
    // Cotangent Laplacian of the flat pattern triangle.
    for (int k = 0; k < 3; ++k) {
      const int i = cloth.F(f, (k + 1) % 3), j = cloth.F(f, (k + 2) % 3);
      const Eigen::Vector2d e1 = u[(k + 1) % 3] - u[k], e2 = u[(k + 2) % 3] - u[k];
      const double cot = e1.dot(e2) / std::abs(e1.x() * e2.y() - e1.y() * e2.x());
      laplace.emplace_back(i, j, -0.5 * cot);
      laplace.emplace_back(j, i, -0.5 * cot);
      laplace.emplace_back(i, i, 0.5 * cot);
      laplace.emplace_back(j, j, 0.5 * cot);
    }
  }
  for (int v = 0; v < n; ++v)
    PIXELCLOTH_CHECK(vertexArea(v) > 0, "solver: cloth vertex " << v << " belongs to no triangle");
  s.mass = options_.density * vertexArea;

  Eigen::SparseMatrix<double> K(n, n), L(n, n);
  K.setFromTriplets(stretch.begin(), stretch.end());
  L.setFromTriplets(laplace.begin(), laplace.end());
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
  PIXELCLOTH_CHECK(s.solver.compute(s.system), "solver: the cloth system could not be factored");
  s.contacts.assign(n, Contact{});
}

QuasistaticSolver::~QuasistaticSolver() = default;
QuasistaticSolver::QuasistaticSolver(QuasistaticSolver&&) noexcept = default;

int QuasistaticSolver::numVertices() const { return static_cast<int>(impl_->mass.size()); }

void QuasistaticSolver::setColliders(std::vector<Collider> colliders, std::vector<int> vertexCollider) {
  PIXELCLOTH_CHECK(static_cast<int>(vertexCollider.size()) == numVertices(),
                   "solver: " << vertexCollider.size() << " collider indices for " << numVertices() << " vertices");
  for (const int c : vertexCollider)
    PIXELCLOTH_CHECK(c >= -1 && c < static_cast<int>(colliders.size()),
                     "solver: collider index " << c << " out of range");
  impl_->colliders.clear();
  for (Collider& collider : colliders) {
    ColliderState state;
    state.mesh = std::move(collider);
    impl_->colliders.push_back(std::move(state));
  }
  impl_->vertexCollider = std::move(vertexCollider);
  impl_->contacts.assign(numVertices(), Contact{});
  impl_->queryNeeded = true;
}

void QuasistaticSolver::moveColliders(const std::vector<Eigen::MatrixX3d>& vertices) {
  PIXELCLOTH_CHECK(vertices.size() == impl_->colliders.size(), "solver: " << vertices.size()
                                                                          << " collider placements for "
                                                                          << impl_->colliders.size() << " colliders");
  for (size_t c = 0; c < vertices.size(); ++c) {
    PIXELCLOTH_CHECK(vertices[c].rows() == impl_->colliders[c].mesh.V.rows(),
                     "solver: collider " << c << " moved with a different vertex count");
    impl_->colliders[c].mesh.V = vertices[c];
    impl_->colliders[c].tree.reset();
  }
  impl_->queryNeeded = true;  // the parts moved towards the cloth: every vertex looks again
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
  for (int it = 0; it < maxIterations; ++it) {
    if (!s.colliders.empty() && (s.queryNeeded || s.sinceQuery >= options_.contactQueryEvery)) {
      s.queryContacts(x, options_.contactActivation);
      s.updateContactWeights(options_.contactStiffness);
    }
    // Local step: nearest rotation (3x2 with orthonormal columns) to each deformation gradient.
    rhs = constant;
    rhs += proximal * s.mass.asDiagonal() * x;
    s.addContactTargets(x, options_.contactOffset, rhs);
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
      s.refreshMovedContacts(x, next, options_.contactActivation);
      s.projectContacts(next, options_.contactOffset);
    }
    report.residual = (next - x).rowwise().norm().maxCoeff();
    x.swap(next);
    ++s.sinceQuery;
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
    const Eigen::Vector3d p = x.row(v);
    auto [face, bary] = s.colliders[c].closest(p);
    const double d = (p - s.colliders[c].pointAt(face, bary)).dot(s.colliders[c].faceNormal(face));
    depth(v) = std::max(0.0, -d);
  }
  return depth;
}

Eigen::VectorXd QuasistaticSolver::areaRatios(const Eigen::MatrixX3d& x) const {
  const Impl& s = *impl_;
  Eigen::VectorXd ratio(s.F.rows());
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = x.row(s.F(f, 0)), b = x.row(s.F(f, 1)), c = x.row(s.F(f, 2));
    ratio(f) = 0.5 * (b - a).cross(c - a).norm() / s.restArea(f);
  }
  return ratio;
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
