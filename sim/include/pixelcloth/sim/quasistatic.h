#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "pixelcloth/core/mesh.h"

namespace pixelcloth::sim {

/// Material and solver settings of the quasistatic cloth solver. Units: SI (metres, kilograms, newtons).
struct QuasistaticOptions {
  double stretchStiffness = 60.0;  ///< membrane stiffness k_s (N/m): energy k_s/2 * area * |F - R|^2 per triangle
  double bendStiffness = 2e-6;     ///< bending stiffness k_b (N m): quadratic (isometric) bending, flat rest shape
  double density = 0.15;           ///< areal density (kg/m^2), a cotton jersey T-shirt
  double gravity = 9.81;           ///< m/s^2 along -y
  /// Proximal time scale h (s): each iteration minimises E(x) + |x - x_k|^2_M / (2 h^2), a fully damped implicit
  /// step, so the iterates descend to the static equilibrium. Larger is faster and less robust; 0.1 s keeps the
  /// sampled T-shirt poses as often as 0.06 s did with 200 final iterations, in 150.
  double timeScale = 0.1;
  double pinStiffness = 1e4;  ///< pins follow their targets with this stiffness (N/m)
  /// Contact: a vertex closer than `contactActivation` to its collider is in contact; its closest point is followed
  /// every iteration by a walk over the collider's faces, and after every iteration the vertex is kept at least
  /// `contactOffset` outside. A vertex further away looks again in the collider's AABB tree as soon as it has moved
  /// that distance (less the activation), so none tunnels through a part.
  double contactOffset = 0.001;
  double contactActivation = 0.02;
  /// Every this many iterations a vertex in contact looks again in the AABB tree instead of walking: a walk ends at
  /// the nearest local minimum of the distance and misses a second sheet of the same part closing in on the vertex
  /// (the shoulder coming down onto the side of the torso part).
  int contactRecheckEvery = 30;
  /// Vertices in contact are held by springs of this stiffness (N/m) in the global step towards an anchor on the body:
  /// the spring's normal force is the body's support, its tangential force friction.
  double contactStiffness = 20.0;
  /// Coulomb friction coefficient of cloth on the body: a vertex in contact sticks (its anchor stays) while the
  /// tangential spring force is at most `friction` times the normal one, and slides beyond. 0: frictionless.
  double friction = 0.3;
  /// No vertex moves further than this in one iteration (metres): keeps the first iterations from a badly compressed
  /// start from throwing cloth through the body. Far above the tolerance, so it does not change the equilibrium.
  double maxStep = 0.005;
  /// Stopping tolerance: the largest vertex move in one iteration (metres). A move of d per iteration means an
  /// unbalanced force per unit mass of about d / h^2: 2e-5 m at h = 0.1 s is 0.002 m/s^2, 0.02% of gravity.
  double tolerance = 2e-5;
  void validate() const;
};

/// A triangle mesh the cloth must stay outside of (a body part), in its current (posed) placement.
struct Collider {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;  ///< oriented outwards
};

/// What one call to `QuasistaticSolver::relax` did.
struct RelaxReport {
  int iterations = 0;
  double residual = 0;  ///< largest vertex move in the last iteration (metres)
  bool converged = false;
};

/// Static equilibrium of cloth under gravity against colliders, by projective dynamics (Bouaziz et al. 2014) with a
/// proximal term instead of inertia: per iteration a local step (each triangle's deformation gradient projected to
/// the nearest rotation) and a global step (one prefactored sparse Cholesky solve, three right-hand sides), followed
/// by contact: each vertex's exact closest point on its collider (a walk over the collider's faces, an AABB tree
/// when far or every `contactRecheckEvery` iterations, inside test by pseudo-normals), Coulomb friction on contact
/// springs anchored to the body, and projection out of the collider. The rest shape of every triangle is its pattern
/// triangle (per-corner UVs in metres), so seams sewn across pattern pieces are rest-free; bending is the quadratic
/// isometric model (Bergou et al. 2006) with a flat rest state. The system matrix is the cloth's and the pins' plus the
/// contact springs, refactored (same sparsity, symbolic analysis reused) when the contact set changes; colliders move
/// and pin targets change freely between calls. Only cloth-body contact is handled, not cloth-cloth (no
/// self-collision).
class QuasistaticSolver {
 public:
  /// `cloth`: faces F plus per-corner pattern coordinates UV / FUV (the rest shape); `pinned`: vertex indices held
  /// at targets (may be empty). Throws InputError for degenerate pattern triangles or missing UVs.
  QuasistaticSolver(const core::Mesh& cloth, const std::vector<int>& pinned, const QuasistaticOptions& options = {});
  ~QuasistaticSolver();
  QuasistaticSolver(QuasistaticSolver&&) noexcept;

  /// Colliders and, per cloth vertex, the index of the one it collides with (-1: none). Lifts a freeze of the contact
  /// springs (freezeContactSprings): they belonged to the old colliders.
  void setColliders(std::vector<Collider> colliders, std::vector<int> vertexCollider);
  /// Moves the colliders' vertices (same faces as before); the next `relax` call looks up every contact again.
  void moveColliders(const std::vector<Eigen::MatrixX3d>& vertices);
  /// Puts the contact springs on the vertices in contact at `x` (#V x 3) and keeps them there from now on: the system
  /// is never refactored, vertices that touch the body later are held by projection alone, those that lift off are
  /// only damped. Every later call then costs no factorisation and its result cannot depend on the calls before it.
  /// For a garment posed many times from one settled drape, freeze at that drape.
  void freezeContactSprings(const Eigen::MatrixX3d& x);
  /// Changes the friction coefficient for the following calls (e.g. 0 to settle a garment fully before posing it).
  void setFriction(double friction);
  /// Changes QuasistaticOptions::contactRecheckEvery for the following calls (more often where a result is measured).
  void setContactRecheckEvery(int iterations);
  /// Targets of the pinned vertices, #pinned x 3, in the order given to the constructor.
  void setPinTargets(const Eigen::MatrixX3d& targets);

  /// Runs at most `maxIterations` iterations from `x` (#V x 3, updated in place); stops early when the largest move
  /// of an iteration falls below the tolerance (unless `minIterations` have not run yet).
  RelaxReport relax(Eigen::MatrixX3d& x, int maxIterations, int minIterations = 0);

  /// Depth of each vertex inside its collider (metres, 0 when outside or without collider), by an exact closest-point
  /// query; inside means behind the closest collider triangle's plane.
  Eigen::VectorXd penetration(const Eigen::MatrixX3d& x) const;
  /// Per triangle, current area over pattern area.
  Eigen::VectorXd areaRatios(const Eigen::MatrixX3d& x) const;
  /// Total potential energy (stretch + bending + gravity + pins), joules; it never increases from one iteration to
  /// the next while no contact is active.
  double energy(const Eigen::MatrixX3d& x) const;

  int numVertices() const;
  const QuasistaticOptions& options() const { return options_; }

 private:
  struct Impl;
  QuasistaticOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pixelcloth::sim
