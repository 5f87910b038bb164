// The Newton equilibrium solver: forces are the energy's gradient, a hanging sheet and a sheet draped over a sphere
// reach the force tolerance, no vertex ever enters the collider or passes through an opening into the part that meets
// it, cloth that a collider folded through itself encloses is moved out of its whole volume, and friction holds cloth
// on a slope.
#include "pixelcloth/sim/equilibrium.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "pixelcloth/core/error.h"
#include "sim_fixtures.h"

namespace pixelcloth::sim {
namespace {

using fixtures::sheet;
using fixtures::sphere;

/// Up to five continuation steps at the same colliders, each of at most `iterations` Newton iterations, until the
/// force tolerance holds.
EquilibriumReport settle(EquilibriumSolver& solver, Eigen::MatrixX3d& x, int iterations) {
  EquilibriumReport report;
  for (int step = 0; step < 5 && !report.converged; ++step) {
    solver.beginStep(x);
    report = solver.solve(x, iterations);
  }
  return report;
}

TEST(Equilibrium, ForcesAreMinusTheEnergyGradientWithContactAndFriction) {
  const core::Mesh cloth = sheet(7, 0.06, 0.1012);
  EquilibriumSolver solver(cloth, {0});
  solver.setPinTargets(cloth.V.row(0) + Eigen::RowVector3d(0.001, 0.002, 0));
  solver.setColliders({sphere(0.1, 48, 96)}, std::vector<int>(cloth.numVertices(), 0));
  // A crumpled, stretched sheet on the sphere's top, with friction lagged a little away from it: some vertices
  // within the friction's static slip, some beyond.
  Eigen::MatrixX3d x = cloth.V;
  for (int v = 0; v < x.rows(); ++v)
    x.row(v) += Eigen::RowVector3d(0.003 * std::sin(3.1 * v), 0.0004 * std::cos(1.7 * v), 0.003 * std::sin(0.9 * v));
  Eigen::MatrixX3d start = x;
  for (int v = 0; v < x.rows(); ++v)
    start.row(v) += Eigen::RowVector3d(0.0015 * std::cos(v), 0, 0.0015 * std::sin(2.0 * v));
  solver.beginStep(start);
  const Eigen::VectorXd d = solver.distances(x);
  ASSERT_GT(d.minCoeff(), 0);
  ASSERT_LT(d.minCoeff(), solver.options().barrierDistance);  // some vertices feel the barrier
  const Eigen::MatrixX3d f = solver.forces(x);
  const double h = 1e-7;
  for (int v = 0; v < x.rows(); v += 5)
    for (int i = 0; i < 3; ++i) {
      Eigen::MatrixX3d plus = x, minus = x;
      plus(v, i) += h;
      minus(v, i) -= h;
      const double numeric = -(solver.energy(plus) - solver.energy(minus)) / (2 * h);
      EXPECT_NEAR(f(v, i), numeric, 1e-5 + 1e-4 * std::abs(numeric)) << "vertex " << v << " axis " << i;
    }
}

TEST(Equilibrium, HangingSheetReachesTheForceTolerance) {
  const int n = 15;
  const core::Mesh cloth = sheet(n, 0.4, 1.0);
  EquilibriumSolver solver(cloth, {0, n - 1});
  Eigen::MatrixX3d targets(2, 3);
  targets.row(0) = cloth.V.row(0);
  targets.row(1) = cloth.V.row(n - 1);
  solver.setPinTargets(targets);
  Eigen::MatrixX3d x = cloth.V;
  solver.beginStep(x);
  const EquilibriumReport report = solver.solve(x, 200);
  EXPECT_TRUE(report.converged) << "force ratio " << report.maxForceRatio << " after " << report.iterations;
  // Linear convergence at the end, where the sheet buckles along its free edge (the projected Hessian drops the
  // compressive directions): 60 iterations today.
  EXPECT_LE(report.iterations, 100);
  const Eigen::VectorXd force = solver.forces(x).rowwise().norm();
  EXPECT_LT(force.cwiseQuotient(solver.weights()).maxCoeff(), solver.options().forceTolerance);
  // It hangs: the free edge has dropped, and the sheet is mirror-symmetric about x = 0.
  EXPECT_LT(x((n - 1) * n + n / 2, 1), 0.75);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) EXPECT_NEAR(x(i * n + j, 0), -x(i * n + n - 1 - j, 0), 1e-4);
}

TEST(Equilibrium, SheetDrapedOverASphereRestsOutsideItAtTheTolerance) {
  // The sheet's centre is pinned just above the sphere's top, so the drape is a stable equilibrium (an unpinned
  // sheet balanced on a sphere slides off one side, which is right but slow to get to).
  const int n = 21;
  const core::Mesh cloth = sheet(n, 0.5, 0.104);
  const int centre = (n / 2) * n + n / 2;
  EquilibriumSolver solver(cloth, {centre});
  solver.setPinTargets(cloth.V.row(centre));
  solver.setColliders({sphere(0.1, 32, 64)}, std::vector<int>(cloth.numVertices(), 0));
  Eigen::MatrixX3d x = cloth.V;
  const EquilibriumReport report = settle(solver, x, 100);
  EXPECT_TRUE(report.converged) << "force ratio " << report.maxForceRatio << " after " << report.iterations;
  const Eigen::VectorXd d = solver.distances(x);
  EXPECT_GT(d.minCoeff(), 0);
  EXPECT_LT(d.minCoeff(), solver.options().barrierDistance);  // it rests on the sphere
  // It hangs down around the sphere: the corners fall below its equator.
  EXPECT_LT(x(0, 1), 0.0);
  EXPECT_GT(solver.areaRatios(x).minCoeff(), 0.25);
}

TEST(Equilibrium, LongerStepsAlongANewtonDirectionThatKeepsLoweringTheEnergySettleInFewerIterations) {
  // The sphere drape above, solved with the line search trying two and four times each full Newton step and with
  // full steps only: both reach the tolerance outside the sphere, the first in fewer iterations.
  const int n = 21;
  const core::Mesh cloth = sheet(n, 0.5, 0.104);
  const int centre = (n / 2) * n + n / 2;
  auto drape = [&](int expansions, Eigen::MatrixX3d& x) {
    EquilibriumOptions options;
    options.stepExpansions = expansions;
    EquilibriumSolver solver(cloth, {centre}, options);
    solver.setPinTargets(cloth.V.row(centre));
    solver.setColliders({sphere(0.1, 32, 64)}, std::vector<int>(cloth.numVertices(), 0));
    x = cloth.V;
    int iterations = 0;
    EquilibriumReport report;
    for (int step = 0; step < 5 && !report.converged; ++step) {
      solver.beginStep(x);
      report = solver.solve(x, 100);
      iterations += report.iterations;
    }
    EXPECT_TRUE(report.converged) << expansions << " expansions: force ratio " << report.maxForceRatio;
    EXPECT_GT(solver.distances(x).minCoeff(), 0);
    return iterations;
  };
  Eigen::MatrixX3d expanded, plain;
  const int fewer = drape(2, expanded), more = drape(0, plain);
  EXPECT_LT(fewer, more);
  // The same drape: the corners hang below the equator either way.
  EXPECT_LT(expanded(0, 1), 0.0);
  EXPECT_LT(plain(0, 1), 0.0);
}

TEST(Equilibrium, FrictionHoldsASheetOnASlopeThatItSlidesOffWithout) {
  // A small sheet on a sphere, off the top by 30 degrees: with mu = 0.9 > tan 30 it sticks near where it starts;
  // frictionless it slides down.
  const core::Mesh flat = sheet(5, 0.04, 0.0);
  const double angle = M_PI / 6, r = 0.2;
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(-angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  core::Mesh cloth = flat;
  for (int v = 0; v < cloth.numVertices(); ++v)
    cloth.V.row(v) = (tilt * (flat.V.row(v).transpose() + Eigen::Vector3d(0, r + 0.001, 0))).transpose();
  auto slide = [&](double friction) {
    EquilibriumOptions options;
    options.friction = friction;
    EquilibriumSolver solver(cloth, {}, options);
    solver.setColliders({sphere(r, 48, 96)}, std::vector<int>(cloth.numVertices(), 0));
    Eigen::MatrixX3d x = cloth.V;
    solver.beginStep(x);
    const Eigen::MatrixX3d start = x;
    const EquilibriumReport report = solver.solve(x, 30);
    return std::make_pair((x - start).rowwise().norm().mean(), report);
  };
  const auto [held, heldReport] = slide(0.9);
  EXPECT_TRUE(heldReport.converged);
  EXPECT_LT(held, 0.002);
  const auto [free, freeReport] = slide(0.0);
  EXPECT_GT(free, 0.02);
}

// Body parts are open where they meet: the torso has a hole where the arm begins. A vertex that keeps off its own
// part alone falls through such an opening; with the parts its own meets it rests on them. Here a floor plate with a
// square hole (the cloth's own collider) and a plug that fills it and overlaps the plate's rim by a cell, as the
// body's parts overlap around the shoulders.
TEST(Equilibrium, ClothKeepsOffThePartsItsOwnMeetsAndDoesNotFallThroughAnOpening) {
  const int cells = 16;
  const double side = 0.4, cell = side / cells;
  Collider plate, plug;
  plate.V.resize((cells + 1) * (cells + 1), 3);
  for (int i = 0; i <= cells; ++i)
    for (int j = 0; j <= cells; ++j) plate.V.row(i * (cells + 1) + j) << j * cell - side / 2, 0, i * cell - side / 2;
  plug.V = plate.V;
  std::vector<Eigen::Vector3i> own, filling;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const int a = i * (cells + 1) + j, b = a + 1, c = a + cells + 1, d = c + 1;
      const auto inside = [&](int margin) {
        return std::min({i, j, cells - 1 - i, cells - 1 - j}) >= cells / 4 - margin;
      };
      for (const Eigen::Vector3i& face : {Eigen::Vector3i(a, c, b), Eigen::Vector3i(b, c, d)}) {
        if (!inside(0)) own.push_back(face);
        if (inside(1)) filling.push_back(face);
      }
    }
  const auto faces = [](const std::vector<Eigen::Vector3i>& list) {
    Eigen::MatrixX3i F(static_cast<int>(list.size()), 3);
    for (int f = 0; f < F.rows(); ++f) F.row(f) = list[f].transpose();
    return F;
  };
  plate.F = faces(own);
  plug.F = faces(filling);

  const int n = 13;
  const core::Mesh cloth = sheet(n, 0.3, 0.004);
  const std::vector<int> corners = {0, n - 1, n * (n - 1), n * n - 1};
  auto drape = [&](bool meets) {
    EquilibriumSolver solver(cloth, corners);
    Eigen::MatrixX3d targets(4, 3);
    for (int k = 0; k < 4; ++k) targets.row(k) = cloth.V.row(corners[k]);
    solver.setPinTargets(targets);
    solver.setColliders({plate, plug}, std::vector<int>(cloth.numVertices(), 0),
                        meets ? std::vector<std::vector<int>>{{1}, {0}} : std::vector<std::vector<int>>{});
    Eigen::MatrixX3d x = cloth.V;
    const EquilibriumReport report = settle(solver, x, 200);
    EXPECT_TRUE(report.converged) << "force ratio " << report.maxForceRatio << " after " << report.iterations;
    return std::make_pair(x, solver.clearances(x));
  };
  const auto [held, clearance] = drape(true);
  EXPECT_GT(held.col(1).minCoeff(), 0.0);  // on the plug
  EXPECT_GT(clearance.minCoeff(), 0.0);
  EXPECT_LT(clearance.minCoeff(), EquilibriumOptions().barrierDistance);
  const auto [fallen, unused] = drape(false);
  EXPECT_LT(fallen.col(1).minCoeff(), -0.002);  // through the hole
}

TEST(Equilibrium, ClothTheBodyCarriedIntoAPartItsOwnMeetsIsLeftThereAndNotHeld) {
  // A sheet pinned at its corners, its middle inside a ball that its own collider (a ball far below) meets, as cloth
  // is when skinning presses an arm into the chest: the ball neither pushes the middle out nor holds it in, so the
  // sheet sags as if the ball were not there; a ball that does not hold the sheet's middle still keeps it off.
  const int n = 13;
  const core::Mesh cloth = sheet(n, 0.3, 0);
  const std::vector<int> corners = {0, n - 1, n * (n - 1), n * n - 1};
  Collider below = sphere(0.05), ball = sphere(0.03);
  below.V.col(1).array() -= 1.0;
  auto drape = [&](std::vector<Collider> colliders, const std::vector<std::vector<int>>& meets, bool& movedAtStart) {
    EquilibriumSolver solver(cloth, corners);
    Eigen::MatrixX3d targets(4, 3);
    for (int k = 0; k < 4; ++k) targets.row(k) = cloth.V.row(corners[k]);
    solver.setPinTargets(targets);
    solver.setColliders(std::move(colliders), std::vector<int>(cloth.numVertices(), 0), meets);
    Eigen::MatrixX3d x = cloth.V;
    solver.beginStep(x);
    movedAtStart = !x.isApprox(cloth.V);
    const EquilibriumReport report = solver.solve(x, 200);
    EXPECT_TRUE(report.converged) << "force ratio " << report.maxForceRatio << " after " << report.iterations;
    return x;
  };
  bool moved = true;
  const Eigen::MatrixX3d through = drape({below, ball}, {{1}, {0}}, moved);
  EXPECT_FALSE(moved);
  const Eigen::MatrixX3d alone = drape({below}, {}, moved);
  EXPECT_LT((through - alone).rowwise().norm().maxCoeff(), 1e-6);
  EXPECT_LT(alone(n * n / 2, 1), -0.03);  // the middle sagged out through the ball's bottom
  // Started above the ball, the sheet rests on it.
  Collider high = ball;
  high.V.col(1).array() -= 0.045;
  const Eigen::MatrixX3d held = drape({below, high}, {{1}, {0}}, moved);
  EXPECT_GT(held(n * n / 2, 1), -0.016);
}

TEST(Equilibrium, ClothAPartFoldedThroughItselfEnclosesIsMovedOutOfItsWholeVolume) {
  // One collider that passes through itself, as a skinned arm does where the bent elbow folds the forearm into the
  // upper arm: a small ball poking out of a large one, both in one mesh. A sheet inside the small ball but nearer
  // the large ball's skin (outside it) reads outside by its nearest sheet; the step's start moves it out of both.
  const Collider large = sphere(0.1), small = sphere(0.05);
  Collider folded;
  folded.V.resize(large.V.rows() + small.V.rows(), 3);
  folded.V << large.V, small.V.rowwise() + Eigen::RowVector3d(0.1, 0, 0);
  folded.F.resize(large.F.rows() + small.F.rows(), 3);
  folded.F << large.F, small.F.array() + static_cast<int>(large.V.rows());
  const int n = 3;
  core::Mesh cloth = sheet(n, 0.004, 0);
  cloth.V.rowwise() += Eigen::RowVector3d(0.111, 0.018, -0.002);
  auto outsideLarge = [](const Eigen::RowVector3d& p) { return p.norm() - 0.1; };
  auto insideSmall = [](const Eigen::RowVector3d& p) { return 0.05 - (p - Eigen::RowVector3d(0.1, 0, 0)).norm(); };
  for (int v = 0; v < cloth.numVertices(); ++v) {
    ASSERT_GT(insideSmall(cloth.V.row(v)), 0.02);
    ASSERT_LT(outsideLarge(cloth.V.row(v)), insideSmall(cloth.V.row(v)) - 0.005);  // the large ball's skin is nearer
    ASSERT_GT(outsideLarge(cloth.V.row(v)), 0.005);
  }
  EquilibriumSolver solver(cloth, {});
  solver.setColliders({folded}, std::vector<int>(cloth.numVertices(), 0));
  ASSERT_GT(solver.distances(cloth.V).minCoeff(), 0);  // the nearest sheet's test: outside
  Eigen::MatrixX3d x = cloth.V;
  solver.beginStep(x);
  for (int v = 0; v < cloth.numVertices(); ++v) {
    EXPECT_LT(insideSmall(x.row(v)), 0) << "vertex " << v << " still inside the small ball";
    EXPECT_GT(outsideLarge(x.row(v)), 0) << "vertex " << v << " moved into the large ball";
    EXPECT_LT((x.row(v) - cloth.V.row(v)).norm(), 0.04) << "vertex " << v << " moved further than out";
  }
  EXPECT_TRUE(std::isfinite(solver.energy(x)));
}

TEST(Equilibrium, ClothOverAPartsOpeningIsNotTakenForClothInsideIt) {
  // Body parts are open where they meet the next. Rays from cloth just over an opening enter through it and leave
  // through a wall, an odd count from outside: a cup 6 cm wide, open at the top, with a sheet 1 cm over its mouth.
  // Only a vertex every ray finds inside is moved out; this one stays where it is.
  Collider cup;
  cup.V.resize(8, 3);
  cup.V << -0.03, 0, -0.03, 0.03, 0, -0.03, 0.03, 0, 0.03, -0.03, 0, 0.03,  //
      -0.03, 0.06, -0.03, 0.03, 0.06, -0.03, 0.03, 0.06, 0.03, -0.03, 0.06, 0.03;
  cup.F.resize(10, 3);
  cup.F << 0, 1, 2, 0, 2, 3,  // bottom, facing -y
      0, 4, 5, 0, 5, 1,       // z = -0.03
      1, 5, 6, 1, 6, 2,       // x = 0.03
      2, 6, 7, 2, 7, 3,       // z = 0.03
      3, 7, 4, 3, 4, 0;       // x = -0.03
  const core::Mesh cloth = sheet(3, 0.004, 0.07);
  EquilibriumSolver solver(cloth, {});
  solver.setColliders({cup}, std::vector<int>(cloth.numVertices(), 0));
  Eigen::MatrixX3d x = cloth.V;
  solver.beginStep(x);
  EXPECT_LT((x - cloth.V).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Equilibrium, ClosestPointsLieOnEachVertexsOwnCollider) {
  const core::Mesh cloth = sheet(5, 0.2, 0.12);
  EquilibriumSolver solver(cloth, {});
  const Collider ball = sphere(0.1);
  std::vector<int> own(cloth.numVertices(), 0);
  own[3] = -1;
  solver.setColliders({ball}, own);
  Eigen::VectorXi face;
  Eigen::MatrixX3d barycentric;
  solver.closestPoints(cloth.V, face, barycentric);
  const Eigen::VectorXd d = solver.distances(cloth.V);
  EXPECT_EQ(face(3), -1);
  for (int v = 0; v < cloth.numVertices(); ++v) {
    if (v == 3) continue;
    ASSERT_GE(face(v), 0);
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) point += barycentric(v, k) * ball.V.row(ball.F(face(v), k)).transpose();
    EXPECT_NEAR((cloth.V.row(v).transpose() - point).norm(), d(v), 1e-12) << "vertex " << v;
    EXPECT_NEAR(barycentric.row(v).sum(), 1.0, 1e-12);
    EXPECT_GE(barycentric.row(v).minCoeff(), 0.0);
  }
}

TEST(Equilibrium, RefusesDegeneratePatternsAndBadSettings) {
  core::Mesh cloth = sheet(3, 0.1, 0);
  EquilibriumOptions options;
  options.barrierDistance = 0;
  EXPECT_THROW(EquilibriumSolver(cloth, {}, options), core::InputError);
  options = {};
  options.stepExpansions = -1;
  EXPECT_THROW(EquilibriumSolver(cloth, {}, options), core::InputError);
  cloth.UV.row(1) = cloth.UV.row(0);
  cloth.UV.row(3) = cloth.UV.row(0);
  EXPECT_THROW(EquilibriumSolver(cloth, {}), core::InputError);
  EXPECT_THROW(EquilibriumSolver(sheet(3, 0.1, 0), {42}), core::InputError);
}

}  // namespace
}  // namespace pixelcloth::sim
