// Harmonic and anisotropic patch bases: partition of unity, linear precision, maximum principle, anisotropic reach,
// on the built-in T-shirt's patches and on a rectangle.
#include "pixelcloth/patches/basis.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

#include "pixelcloth/core/error.h"
#include "pixelcloth/garment/garment.h"

namespace pp = pixelcloth::patches;
namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;

namespace {

/// The T-shirt cut along its armhole seams: 6 patches (per layout: torso and two sleeve halves).
std::vector<pp::PatchMesh> shirtPatches() {
  static const std::vector<pp::PatchMesh> meshes = [] {
    pg::Garment shirt = pg::makeTShirt();
    std::vector<std::pair<int, int>> cuts;
    for (const pg::Seam& seam : shirt.seams)
      if (!seam.joinsLayouts)
        for (size_t i = 0; i + 1 < seam.vertices.size(); ++i) cuts.emplace_back(seam.vertices[i], seam.vertices[i + 1]);
    std::vector<pp::PatchMesh> out;
    for (const pp::Patch& p : pp::segmentPatches(shirt, cuts)) out.push_back(pp::patchMesh(shirt, p));
    return out;
  }();
  return meshes;
}

pp::BasisOptions anisotropic(double theta, double ratio) {
  pp::BasisOptions o;
  o.anisotropic = true;
  o.theta = theta;
  o.ratio = ratio;
  return o;
}

/// The option sets every property is checked with.
std::vector<pp::BasisOptions> optionSets() {
  return {pp::BasisOptions{}, anisotropic(0.5, 0.1), anisotropic(2.0, 0.3)};
}

/// Every test patch: the six T-shirt patches and a 0.2 m square.
std::vector<pp::PatchMesh> testPatches() {
  std::vector<pp::PatchMesh> all = shirtPatches();
  all.push_back(pp::rectanglePatch(0.2, 0.2, 20, 20));
  return all;
}

Eigen::MatrixX3d boundaryRows(const pp::PatchMesh& patch, const Eigen::MatrixX3d& perVertex) {
  Eigen::MatrixX3d b(patch.boundary.size(), 3);
  for (size_t j = 0; j < patch.boundary.size(); ++j) b.row(j) = perVertex.row(patch.boundary[j]);
  return b;
}

/// Distance from `origin` along unit `direction` at which `values` (#n, per local vertex) first drops below
/// `threshold`, linearly interpolated between the vertices that lie on the ray.
double rayExtent(const pp::PatchMesh& patch, const Eigen::VectorXd& values, const Eigen::Vector2d& origin,
                 const Eigen::Vector2d& direction, double threshold) {
  std::vector<std::pair<double, double>> samples;  // (distance, value)
  for (int v = 0; v < patch.uv.rows(); ++v) {
    Eigen::Vector2d d = patch.uv.row(v).transpose() - origin;
    double t = d.dot(direction);
    if (t >= -1e-12 && (d - t * direction).norm() < 1e-9) samples.emplace_back(t, values(v));
  }
  std::sort(samples.begin(), samples.end());
  for (size_t k = 1; k < samples.size(); ++k)
    if (samples[k].second < threshold) {
      auto [t0, v0] = samples[k - 1];
      auto [t1, v1] = samples[k];
      return t0 + (v0 - threshold) / (v0 - v1) * (t1 - t0);
    }
  return samples.back().first;
}

}  // namespace

TEST(PatchBasis, ShirtPatchesHaveTheExpectedShape) {
  std::vector<pp::PatchMesh> patches = shirtPatches();
  ASSERT_EQ(patches.size(), 6u);
  for (const pp::PatchMesh& patch : patches) {
    pp::PatchBasis basis(patch);
    EXPECT_EQ(basis.matrix().rows(), static_cast<int>(patch.interior.size()));
    EXPECT_EQ(basis.matrix().cols(), static_cast<int>(patch.boundary.size()));
    std::cout << "measured: shirt patch " << patch.uv.rows() << " vertices, " << patch.boundary.size() << " boundary\n";
  }
}

TEST(PatchBasis, PartitionOfUnity) {
  double worst = 0;
  for (const pp::BasisOptions& options : optionSets())
    for (const pp::PatchMesh& patch : testPatches()) {
      pp::PatchBasis basis(patch, options);
      worst = std::max(worst, (basis.matrix().rowwise().sum().array() - 1.0).abs().maxCoeff());
    }
  std::cout << "measured: max |row sum - 1| = " << worst << "\n";
  EXPECT_LT(worst, 1e-9);
}

TEST(PatchBasis, ReproducesLinearBoundaryData) {
  // u(x) = a + B x for each of the three channels; exact for P1 elements with any constant tensor D, because the
  // Galerkin residual of a linear function at an interior vertex is the integral of grad(phi_i) . (D c) = 0.
  Eigen::RowVector3d a(0.3, -1.0, 2.0);
  Eigen::Matrix<double, 2, 3> B;
  B << 1.5, -0.7, 4.0, 0.2, 3.0, -2.5;
  double worst = 0;
  for (const pp::BasisOptions& options : optionSets())
    for (const pp::PatchMesh& patch : testPatches()) {
      Eigen::MatrixX3d exact = (patch.uv * B).rowwise() + a;
      pp::PatchBasis basis(patch, options);
      Eigen::MatrixX3d all = basis.fillAll(boundaryRows(patch, exact));
      worst = std::max(worst, (all - exact).cwiseAbs().maxCoeff());
    }
  std::cout << "measured: linear reproduction max error = " << worst << "\n";
  EXPECT_LT(worst, 1e-9);
}

TEST(PatchBasis, MaximumPrinciple) {
  // Isotropic on the square's non-obtuse mesh and on the T-shirt's Delaunay meshes (min angle 20.7 degrees): the
  // interior stiffness is an M-matrix, so every weight lies in [0, 1].
  double isoMin = 1, isoMax = 0;
  for (const pp::PatchMesh& patch : testPatches()) {
    pp::PatchBasis basis(patch);
    isoMin = std::min(isoMin, basis.matrix().minCoeff());
    isoMax = std::max(isoMax, basis.matrix().maxCoeff());
  }
  std::cout << "measured: isotropic entries in [" << isoMin << ", " << isoMax << "]\n";
  EXPECT_GE(isoMin, -1e-12);
  EXPECT_LE(isoMax, 1 + 1e-12);
  // Anisotropic: the P1 stiffness is an M-matrix only if the mesh is Delaunay in the metric of D^-1; a strong tensor
  // not aligned with the mesh makes some couplings positive and negative weights appear next to the boundary.
  // Measured (T-shirt patches and the square): ratio 0.1 down to -0.214, ratio 0.3 down to -0.099; bounded here.
  for (const pp::BasisOptions& options : {anisotropic(0.5, 0.1), anisotropic(2.0, 0.3)}) {
    double anisoMin = 1, anisoMax = 0;
    for (const pp::PatchMesh& patch : testPatches()) {
      pp::PatchBasis basis(patch, options);
      anisoMin = std::min(anisoMin, basis.matrix().minCoeff());
      anisoMax = std::max(anisoMax, basis.matrix().maxCoeff());
    }
    std::cout << "measured: anisotropic ratio " << options.ratio << ", entries in [" << anisoMin << ", " << anisoMax
              << "]\n";
    EXPECT_GE(anisoMin, options.ratio < 0.2 ? -0.25 : -0.12);
    EXPECT_LE(anisoMax, 1 + 1e-12);
  }
}

TEST(PatchBasis, AnisotropicInfluenceReachesFurtherAlongTheta) {
  // 0.2 m square, 5 mm cells; the basis function of the bottom edge's midpoint (0.1, 0).
  pp::PatchMesh square = pp::rectanglePatch(0.2, 0.2, 40, 40);
  const Eigen::Vector2d origin(0.1, 0.0);
  const int column = 20;  // boundary loop starts at (0, 0) and runs along the bottom edge
  ASSERT_LT((square.uv.row(square.boundary[column]).transpose() - origin).norm(), 1e-12);
  const double ratio = 0.25;
  auto columnValues = [&](const pp::BasisOptions& options) {
    Eigen::MatrixX3d data = Eigen::MatrixX3d::Zero(square.boundary.size(), 3);
    data(column, 0) = 1.0;
    return Eigen::VectorXd(pp::PatchBasis(square, options).fillAll(data).col(0));
  };
  const Eigen::Vector2d up(0, 1), diag(std::sqrt(0.5), std::sqrt(0.5)), antiDiag(-std::sqrt(0.5), std::sqrt(0.5));

  // One basis, theta = 45 degrees: reach along the 45-degree ray vs along the 135-degree ray (across theta).
  Eigen::VectorXd tilted = columnValues(anisotropic(M_PI / 4, ratio));
  double along = rayExtent(square, tilted, origin, diag, 0.1),
         across = rayExtent(square, tilted, origin, antiDiag, 0.1);
  // Two bases, same ray (straight up): theta = 90 degrees (along) vs theta = 0 (across), and isotropic.
  double upAlong = rayExtent(square, columnValues(anisotropic(M_PI / 2, ratio)), origin, up, 0.1);
  double upAcross = rayExtent(square, columnValues(anisotropic(0.0, ratio)), origin, up, 0.1);
  double upIso = rayExtent(square, columnValues({}), origin, up, 0.1);
  std::cout << "measured: ratio " << ratio << ", extent to 0.1: theta 45 deg along " << along << " m, across " << across
            << " m (x" << along / across << "); straight up: along " << upAlong << " m, isotropic " << upIso
            << " m, across " << upAcross << " m (x" << upAlong / upAcross << ")\n";
  EXPECT_GT(along, 2.0 * across);
  EXPECT_GT(upAlong, 1.5 * upIso);
  EXPECT_GT(upIso, 1.5 * upAcross);
  EXPECT_GT(upAlong, 3.0 * upAcross);
}

TEST(PatchBasis, OneShotFillAndFillAllAgree) {
  pp::PatchMesh patch = shirtPatches()[1];
  Eigen::MatrixX3d data = Eigen::MatrixX3d::Random(patch.boundary.size(), 3);
  pp::BasisOptions options = anisotropic(1.0, 0.2);
  pp::PatchBasis basis(patch, options);
  Eigen::MatrixX3d inside = basis.fill(data);
  EXPECT_LT((pp::fillPatch(patch, data, options) - inside).cwiseAbs().maxCoeff(), 1e-14);
  Eigen::MatrixX3d all = basis.fillAll(data);
  for (size_t j = 0; j < patch.boundary.size(); ++j) EXPECT_EQ(all.row(patch.boundary[j]), data.row(j));
  for (size_t i = 0; i < patch.interior.size(); ++i) EXPECT_EQ(all.row(patch.interior[i]), inside.row(i));
}

TEST(PatchBasis, RejectsBadInput) {
  pp::PatchMesh square = pp::rectanglePatch(0.2, 0.1, 4, 2);
  pp::PatchBasis basis(square);
  EXPECT_THROW(basis.fill(Eigen::MatrixX3d::Zero(square.boundary.size() - 1, 3)), pc::InputError);
  Eigen::MatrixX3d nan = Eigen::MatrixX3d::Zero(square.boundary.size(), 3);
  nan(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(basis.fill(nan), pc::InputError);
  EXPECT_THROW(pp::PatchBasis(square, anisotropic(0.0, 0.0)), pc::InputError);
  EXPECT_THROW(pp::PatchBasis(square, anisotropic(0.0, 1.5)), pc::InputError);
  EXPECT_THROW(pp::PatchBasis(square, anisotropic(std::nan(""), 0.5)), pc::InputError);
  pp::BasisOptions ignored;  // theta and ratio are not used when isotropic
  ignored.ratio = -1;
  EXPECT_NO_THROW(pp::PatchBasis(square, ignored));

  pp::PatchMesh degenerate = square;
  degenerate.uv.row(degenerate.interior.back()) << 0.175, 0.05;  // the last cell's centre onto its bottom edge
  EXPECT_THROW(pp::PatchBasis{degenerate}, pc::InputError);
  pp::PatchMesh flipped = square;
  flipped.F.row(0) = Eigen::RowVector3i(flipped.F(0, 1), flipped.F(0, 0), flipped.F(0, 2));
  EXPECT_THROW(pp::PatchBasis{flipped}, pc::InputError);
  pp::PatchMesh missing = square;
  missing.interior.pop_back();
  EXPECT_THROW(pp::PatchBasis{missing}, pc::InputError);
  pp::PatchMesh outOfRange = square;
  outOfRange.F(3, 2) = 1000;
  EXPECT_THROW(pp::PatchBasis{outOfRange}, pc::InputError);
  EXPECT_THROW(pp::rectanglePatch(0.0, 0.1, 4, 4), pc::InputError);
  EXPECT_THROW(pp::rectanglePatch(0.1, 0.1, 0, 4), pc::InputError);
}
