#include "pixelcloth/sim/quasistatic.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh.h"
#include "sim_fixtures.h"
#include "support/test_util.h"

namespace pixelcloth::sim {
namespace {

using fixtures::sheet;
using fixtures::sphere;

TEST(Quasistatic, HangingSheetConvergesSymmetricallyWithEnergyNeverRising) {
  const int n = 15;
  const core::Mesh cloth = sheet(n, 0.4, 1.0);
  // Pin the two corners of one edge (row 0), so the sheet hangs like a curtain.
  const std::vector<int> pins = {0, n - 1};
  QuasistaticSolver solver(cloth, pins);
  Eigen::MatrixX3d targets(2, 3);
  targets.row(0) = cloth.V.row(0);
  targets.row(1) = cloth.V.row(n - 1);
  solver.setPinTargets(targets);

  Eigen::MatrixX3d x = cloth.V;
  double previous = solver.energy(x);
  for (int round = 0; round < 40; ++round) {
    solver.relax(x, 5);
    const double e = solver.energy(x);
    EXPECT_LE(e, previous + 1e-12) << "round " << round;
    previous = e;
  }
  const RelaxReport report = solver.relax(x, 3000);
  EXPECT_TRUE(report.converged) << "residual " << report.residual;
  EXPECT_TRUE(x.allFinite());
  // It fell: the free edge hangs well below the pinned one.
  EXPECT_LT(x(n * (n - 1) + n / 2, 1), 0.75);
  // Mirror symmetry about the plane x = 0: vertex (i, j) mirrors (i, n-1-j).
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector3d a = x.row(i * n + j), b = x.row(i * n + n - 1 - j);
      EXPECT_NEAR(a.x(), -b.x(), 1e-4);
      EXPECT_NEAR(a.y(), b.y(), 1e-4);
    }
  // Cloth barely stretches under its own weight: most triangles keep their area within 5%; next to the two pins,
  // which carry all the weight, within 25%.
  Eigen::VectorXd ratio = solver.areaRatios(x);
  std::sort(ratio.data(), ratio.data() + ratio.size());
  EXPECT_NEAR(ratio(ratio.size() / 2), 1.0, 0.05);
  EXPECT_LT(ratio.maxCoeff(), 1.25);
}

TEST(Quasistatic, SheetDrapesOverSphereWithoutPassingThrough) {
  const int n = 31;
  const double radius = 0.2;
  const core::Mesh cloth = sheet(n, 0.7, radius + 0.02);
  // Without friction a sheet slides off a ball, so its centre is pinned 2 mm above the top of the sphere.
  const int centre = (n / 2) * n + n / 2;
  QuasistaticOptions frictionless;
  frictionless.friction = 0;
  QuasistaticSolver solver(cloth, {centre}, frictionless);
  solver.setPinTargets(Eigen::RowVector3d(0, radius + 0.002, 0));
  solver.setColliders({sphere(radius)}, std::vector<int>(n * n, 0));
  Eigen::MatrixX3d x = cloth.V;
  const RelaxReport report = solver.relax(x, 6000);
  EXPECT_TRUE(report.converged) << "residual " << report.residual << " after " << report.iterations;
  EXPECT_TRUE(x.allFinite());
  EXPECT_LT(solver.penetration(x).maxCoeff(), 0.002);
  // The corners hang down past the equator, and no vertex is inside the ball (the polygonal sphere lies inside
  // the true one by at most r (1 - cos(pi / 24))).
  EXPECT_LT(x(0, 1), 0.0);
  EXPECT_GT(x.rowwise().norm().minCoeff(), radius * std::cos(M_PI / 24) - 0.002);
  // Triangles keep their area within 5% (median); the most stretched one is next to the pin.
  Eigen::VectorXd ratio = solver.areaRatios(x);
  std::sort(ratio.data(), ratio.data() + ratio.size());
  EXPECT_NEAR(ratio(ratio.size() / 2), 1.0, 0.05);
  EXPECT_LT(ratio.maxCoeff(), 1.4);
}

/// A closed axis-aligned box [lo, hi], faces outwards.
Collider box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Collider b;
  b.V.resize(8, 3);
  for (int k = 0; k < 8; ++k)
    b.V.row(k) << (k & 1 ? hi.x() : lo.x()), (k & 2 ? hi.y() : lo.y()), (k & 4 ? hi.z() : lo.z());
  b.F.resize(12, 3);
  b.F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5;
  return b;
}

/// A square of cloth lying on a slab tilted by `degrees` about the z axis: how far its centre has moved along the
/// slope after relaxing under gravity with friction coefficient `friction`.
double slideOnSlope(double degrees, double friction) {
  const int n = 11;
  core::Mesh cloth = sheet(n, 0.2, 0.0011);
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  cloth.V = (cloth.V * tilt.transpose()).eval();
  Collider slab = box({-1, -0.1, -1}, {1, 0, 1});
  slab.V = (slab.V * tilt.transpose()).eval();
  QuasistaticOptions options;
  options.friction = friction;
  QuasistaticSolver solver(cloth, {}, options);
  solver.setColliders({slab}, std::vector<int>(n * n, 0));
  Eigen::MatrixX3d x = cloth.V;
  // Sliding is slow: the contact springs let a vertex slip by (net force) / stiffness per iteration, a few microns
  // here, below the stopping tolerance; so run a fixed number of iterations.
  solver.relax(x, 10000, 10000);
  EXPECT_LT(solver.penetration(x).maxCoeff(), 1e-4);
  const Eigen::Vector3d downhill = tilt * Eigen::Vector3d(-1, 0, 0);  // the slab's surface falls towards -x
  return (x.colwise().mean() - cloth.V.colwise().mean()).dot(downhill.transpose());
}

TEST(Quasistatic, FrictionHoldsClothOnAGentleSlopeAndNotOnASteepOne) {
  // Coulomb: cloth sticks while tan(slope) <= friction. tan(10 deg) = 0.18 and tan(30 deg) = 0.58 against 0.3.
  const double gentle = slideOnSlope(10, 0.3), steep = slideOnSlope(30, 0.3), slippery = slideOnSlope(10, 0.0);
  EXPECT_LT(std::abs(gentle), 0.001) << "gentle slope with friction";
  EXPECT_GT(steep, 0.01) << "steep slope with friction";
  EXPECT_GT(slippery, 0.01) << "gentle slope without friction";
}

TEST(Quasistatic, CollidersMoveAndTheClothFollows) {
  const int n = 21;
  const core::Mesh cloth = sheet(n, 0.5, 0.01);
  QuasistaticSolver solver(cloth, {});
  const Collider table = box({-1, -0.1, -1}, {1, 0, 1});
  ASSERT_GT(core::enclosedVolume(table.V, table.F), 0);
  solver.setColliders({table}, std::vector<int>(n * n, 0));
  Eigen::MatrixX3d x = cloth.V;
  EXPECT_TRUE(solver.relax(x, 3000).converged);
  const double before = x.col(1).mean();
  EXPECT_NEAR(before, solver.options().contactOffset, 1e-4);
  // Lift the table by 5 cm in steps: the cloth rides up with it and stays flat.
  for (int step = 1; step <= 5; ++step) {
    Eigen::MatrixX3d moved = table.V;
    moved.col(1).array() += 0.01 * step;
    solver.moveColliders({moved});
    solver.relax(x, 100);
  }
  EXPECT_TRUE(solver.relax(x, 3000).converged);
  EXPECT_NEAR(x.col(1).mean() - before, 0.05, 1e-4);
  EXPECT_LT(x.col(1).maxCoeff() - x.col(1).minCoeff(), 1e-4);
  EXPECT_LT(solver.penetration(x).maxCoeff(), 1e-6);
}

TEST(Quasistatic, BadInputIsRefused) {
  core::Mesh cloth = sheet(4, 0.1, 0.0);
  core::Mesh noUV = cloth;
  noUV.UV.resize(0, 2);
  noUV.FUV.resize(0, 3);
  EXPECT_NE(testing::inputErrorOf([&] { QuasistaticSolver s(noUV, {}); }).find("pattern coordinates"),
            std::string::npos);
  core::Mesh degenerate = cloth;
  degenerate.UV.row(degenerate.FUV(0, 1)) = degenerate.UV.row(degenerate.FUV(0, 0));
  EXPECT_NE(testing::inputErrorOf([&] { QuasistaticSolver s(degenerate, {}); }).find("degenerate"), std::string::npos);
  EXPECT_NE(testing::inputErrorOf([&] { QuasistaticSolver s(cloth, {99}); }).find("pinned vertex 99"),
            std::string::npos);
  QuasistaticSolver solver(cloth, {});
  EXPECT_NE(testing::inputErrorOf([&] { solver.setColliders({}, std::vector<int>(16, 0)); }).find("out of range"),
            std::string::npos);
  Eigen::MatrixX3d wrong = Eigen::MatrixX3d::Zero(3, 3);
  EXPECT_NE(testing::inputErrorOf([&] { solver.relax(wrong, 1); }).find("3 positions for 16"), std::string::npos);
  QuasistaticOptions options;
  options.timeScale = -1;
  EXPECT_NE(testing::inputErrorOf([&] { QuasistaticSolver s(cloth, {}, options); }).find("time scale"),
            std::string::npos);
}

}  // namespace
}  // namespace pixelcloth::sim
