#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "pixelcloth/core/mesh.h"
#include "pixelcloth/sim/quasistatic.h"

namespace pixelcloth::sim {

/// Material, contact and stopping settings of the Newton equilibrium solver. Units: SI (metres, kilograms, newtons).
struct EquilibriumOptions {
  /// Membrane stiffness k_s (N/m): energy k_s/2 * area * sum_i w_i (s_i - 1)^2 per triangle over the singular values
  /// s_i of its deformation gradient, w_i = 1 in tension (s_i > 1).
  double stretchStiffness = 60.0;
  /// w_i in compression (s_i < 1), as a fraction of the tension stiffness: cloth buckles long before it compresses
  /// in its plane. 1 is as-rigid-as-possible (k_s/2 * area * |F - R|^2).
  double compressionRatio = 1.0;
  double bendStiffness = 2e-6;  ///< bending stiffness k_b (N m): quadratic (isometric) bending, flat rest shape
  double density = 0.15;        ///< areal density (kg/m^2), a cotton jersey T-shirt
  double gravity = 9.81;        ///< m/s^2 along -y
  double pinStiffness = 1e4;    ///< pins follow their targets with this stiffness (N/m)
  /// Contact: IPC's log barrier kappa_v b(d), b(d) = -(d - dhat)^2 ln(d / dhat) for 0 < d < dhat, on the signed
  /// distance d of each cloth vertex to its collider. `barrierDistance` is dhat (metres); a vertex never gets closer
  /// than 0 (the energy is infinite there, so the line search keeps every vertex outside).
  double barrierDistance = 0.002;
  /// kappa_v is this times the vertex's cloth area (N/m^3): a pressure of 100 Pa holds cloth about 1 mm off the body.
  double barrierStiffness = 5e4;
  /// Coulomb friction coefficient of cloth on the body, lagged as in IPC: the normal force and tangent plane of each
  /// contact are fixed at the start of a continuation step (beginStep), and a tangential slide u from there costs
  /// mu lambda f0(|u|), IPC's smoothed static friction. 0: frictionless.
  double friction = 0.3;
  /// Slide below which friction acts as a spring (IPC's eps_v h, metres): static friction within this, sliding beyond.
  double frictionSlip = 0.001;
  /// Stopping test: the largest net force on a vertex, as a fraction of that vertex's weight (m_v g).
  double forceTolerance = 0.01;
  /// No vertex moves further than this in one Newton step (metres): a step is scaled down to it before the line
  /// search, so no vertex jumps through a body part.
  double maxMove = 0.02;
  /// After a full Newton step the line search also tries 2, 4, ... 2^stepExpansions times that step (within
  /// maxMove) and keeps the longest whose energy is lower than the shorter one's. The projected Hessian
  /// overestimates the stiffness where cloth buckles or slides over the body (the projection drops the negative
  /// curvature of compressed triangles and of the barrier over edges and corners), so a full step often stops short.
  int stepExpansions = 2;
  void validate() const;
};

/// What one call to `EquilibriumSolver::solve` did.
struct EquilibriumReport {
  int iterations = 0;        ///< Newton iterations
  double maxForce = 0;       ///< largest net force on a vertex at the end (N)
  double maxForceRatio = 0;  ///< the same over that vertex's weight (the stopping test's measure)
  double lastMove = 0;       ///< largest vertex move of the last step (metres)
  bool converged = false;    ///< maxForceRatio below EquilibriumOptions::forceTolerance
  bool stalled = false;      ///< the line search found no decrease (numerical floor reached or a bad direction)
};

/// Static equilibrium of cloth under gravity against colliders, by energy minimisation with Newton's method
/// (DESIGN.md "Simulation"): stretch (as-rigid-as-possible membrane from the flat pattern, per-corner UVs in metres),
/// quadratic isometric bending (Bergou et al. 2006), gravity, pins, contact with each vertex's own collider as IPC's
/// log barrier (Li et al. 2020) on the exact signed distance, and IPC's lagged smoothed friction. Each Newton step
/// solves with the Hessian, every triangle's stretch Hessian projected to positive semi-definite in closed form from
/// its singular values, by a sparse Cholesky factorisation (CHOLMOD, supernodal; symbolic analysis done once); then a
/// backtracking line search on the total energy, on which a vertex inside its collider costs infinitely much (after a
/// full step it tries longer ones, `stepExpansions`). It stops when the largest net force on a vertex is below
/// `forceTolerance` of its weight. Colliders stay put during a solve and move freely between calls. Only cloth-body
/// contact, no self-collision.
class EquilibriumSolver {
 public:
  /// `cloth`: faces F plus per-corner pattern coordinates UV / FUV (the rest shape); `pinned`: vertex indices held
  /// at targets (may be empty). Throws InputError for degenerate pattern triangles or missing UVs.
  EquilibriumSolver(const core::Mesh& cloth, const std::vector<int>& pinned, const EquilibriumOptions& options = {});
  ~EquilibriumSolver();
  EquilibriumSolver(EquilibriumSolver&&) noexcept;

  /// Colliders and, per cloth vertex, the index of its own (-1: none). `meets[c]` (empty: none) lists the colliders
  /// that collider c meets (body parts open where they join): a vertex of c keeps off their surfaces too, so that it
  /// cannot pass through c's opening into the space the neighbouring part fills. Inside and outside (distances(),
  /// the penetration test) stay measured against the vertex's own collider.
  void setColliders(std::vector<Collider> colliders, std::vector<int> vertexCollider,
                    const std::vector<std::vector<int>>& meets = {});
  /// Moves the colliders' vertices (same faces as before).
  void moveColliders(const std::vector<Eigen::MatrixX3d>& vertices);
  /// Targets of the pinned vertices, #pinned x 3, in the order given to the constructor.
  void setPinTargets(const Eigen::MatrixX3d& targets);
  /// Changes the friction coefficient for the following steps (0: frictionless).
  void setFriction(double friction);

  /// Starts a continuation step at `x` (#V x 3), with the colliders where they now are: vertices closer to their
  /// collider than a quarter of the barrier distance (or inside it) are moved out along the contact normal to half
  /// of it, so the solve starts where the barrier is finite; then friction is lagged at `x` (normal forces, tangent
  /// planes and the points slides are measured from).
  void beginStep(Eigen::MatrixX3d& x);
  /// Lags friction again at `x` and keeps the step's start points (IPC's lagged iteration, for the final pose), but
  /// no contact's friction grows: each vertex's lagged friction force becomes the smaller of the lagged one and
  /// `ease` times the Coulomb bound at `x` (mu times the barrier's normal force there; zero where the contact let
  /// go), its tangent plane the one at `x`. Since the lagged forces only fall, repeated lags end within the Coulomb
  /// bound (coulombExcess) instead of cycling between a contact that holds and one that lets go; `ease` below 1
  /// leaves room for the next solve to ease a contact further, so fewer lags are needed.
  void updateFriction(const Eigen::MatrixX3d& x, double ease = 1);
  /// Newton iterations from `x` (updated in place) until the stopping test holds or `maxIterations` have run.
  /// `forceTolerance` > 0 overrides the options' for this call (a looser test on intermediate steps).
  EquilibriumReport solve(Eigen::MatrixX3d& x, int maxIterations, double forceTolerance = 0);

  /// Net force on every vertex at `x` (#V x 3, newtons): minus the gradient of the total energy, friction included.
  Eigen::MatrixX3d forces(const Eigen::MatrixX3d& x) const;
  /// Per vertex, how far its lagged friction force at `x` exceeds the Coulomb bound mu times the normal force the
  /// barrier exerts there now (newtons, >= 0). Nonzero where a contact let go or pressed less since friction was
  /// lagged: such a state balances only with friction that no contact provides, so it is not yet an equilibrium
  /// (lag again: updateFriction).
  Eigen::VectorXd coulombExcess(const Eigen::MatrixX3d& x) const;
  /// Signed distance of each vertex to its collider (metres; negative inside; +infinity without collider), exact.
  Eigen::VectorXd distances(const Eigen::MatrixX3d& x) const;
  /// Per vertex, the closest point of its own collider: the collider's face (-1 without collider) and the point's
  /// barycentric coordinates in it (#V x 3).
  void closestPoints(const Eigen::MatrixX3d& x, Eigen::VectorXi& face, Eigen::MatrixX3d& barycentric) const;
  /// Distance of each vertex to the nearest surface it keeps off, its own collider's or one that collider meets
  /// (metres, unsigned; +infinity without collider): the barrier acts on a vertex closer than its distance.
  Eigen::VectorXd clearances(const Eigen::MatrixX3d& x) const;
  /// Per triangle, current area over pattern area.
  Eigen::VectorXd areaRatios(const Eigen::MatrixX3d& x) const;
  /// Total energy (J) relative to `x`'s own gravity reference 0: stretch + bending + gravity + pins + barrier +
  /// friction; +infinity when a vertex is inside its collider.
  double energy(const Eigen::MatrixX3d& x) const;
  /// Per vertex, its weight m_v g (N).
  const Eigen::VectorXd& weights() const;

  int numVertices() const;
  const EquilibriumOptions& options() const { return options_; }

 private:
  struct Impl;
  EquilibriumOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pixelcloth::sim
