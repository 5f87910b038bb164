// Harmonic / anisotropic-diffusion blendshape bases of a patch (paper's appendix): P1 finite elements in pattern space.
#include "pixelcloth/patches/basis.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cmath>

#include "pixelcloth/core/error.h"

namespace pixelcloth::patches {

void BasisOptions::validate() const {
  if (!anisotropic) return;
  PIXELCLOTH_CHECK(std::isfinite(theta), "basis options: theta must be a finite angle in radians, got " << theta);
  PIXELCLOTH_CHECK(ratio > 0.0 && ratio <= 1.0,
                   "basis options: ratio (diffusion across theta relative to along) must be in (0, 1], got " << ratio);
}

Eigen::Matrix2d BasisOptions::tensor() const {
  if (!anisotropic) return Eigen::Matrix2d::Identity();
  Eigen::Matrix2d rotation;
  rotation << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  return rotation * Eigen::Vector2d(1.0, ratio).asDiagonal() * rotation.transpose();
}

PatchBasis::PatchBasis(const PatchMesh& patch, const BasisOptions& options)
    : options_(options), boundary_(patch.boundary), interior_(patch.interior) {
  options.validate();
  const int n = static_cast<int>(patch.uv.rows());
  numVertices_ = n;
  PIXELCLOTH_CHECK(!boundary_.empty(), "patch basis: the patch has no boundary vertices");
  PIXELCLOTH_CHECK(patch.uv.allFinite(), "patch basis: the patch has non-finite uv coordinates");
  // Each vertex is either on the boundary (column index) or interior (row index).
  std::vector<int> role(n, -1);  // >= 0: interior row; <= -2: boundary column -2 - j
  for (size_t j = 0; j < boundary_.size(); ++j) {
    int v = boundary_[j];
    PIXELCLOTH_CHECK(v >= 0 && v < n,
                     "patch basis: boundary vertex " << v << " is out of range (" << n << " vertices)");
    PIXELCLOTH_CHECK(role[v] == -1, "patch basis: vertex " << v << " appears twice in the boundary loop");
    role[v] = -2 - static_cast<int>(j);
  }
  for (size_t i = 0; i < interior_.size(); ++i) {
    int v = interior_[i];
    PIXELCLOTH_CHECK(v >= 0 && v < n,
                     "patch basis: interior vertex " << v << " is out of range (" << n << " vertices)");
    PIXELCLOTH_CHECK(role[v] == -1, "patch basis: vertex " << v << " is listed twice (boundary or interior)");
    role[v] = static_cast<int>(i);
  }
  for (int v = 0; v < n; ++v)
    PIXELCLOTH_CHECK(role[v] != -1, "patch basis: vertex " << v << " is neither in the boundary nor in the interior");

  const int ni = numInterior(), nb = numBoundary();
  const Eigen::Matrix2d D = options.tensor();
  std::vector<Eigen::Triplet<double>> kii, kib;
  kii.reserve(9 * patch.F.rows());
  kib.reserve(6 * patch.F.rows());
  for (int f = 0; f < patch.F.rows(); ++f) {
    int idx[3];
    Eigen::Vector2d p[3];
    for (int k = 0; k < 3; ++k) {
      idx[k] = patch.F(f, k);
      PIXELCLOTH_CHECK(idx[k] >= 0 && idx[k] < n,
                       "patch basis: triangle " << f << " uses vertex " << idx[k] << ", but the patch has " << n);
      p[k] = patch.uv.row(idx[k]).transpose();
    }
    Eigen::Vector2d e[3];  // e[k]: edge opposite corner k, counter-clockwise
    double longest = 0;
    for (int k = 0; k < 3; ++k) {
      e[k] = p[(k + 2) % 3] - p[(k + 1) % 3];
      longest = std::max(longest, e[k].squaredNorm());
    }
    const double twiceArea = e[2].x() * (-e[1].y()) - e[2].y() * (-e[1].x());  // (p1 - p0) x (p2 - p0)
    PIXELCLOTH_CHECK(twiceArea > 2e-12 * longest, "patch basis: triangle " << f << " (" << idx[0] << ", " << idx[1]
                                                                           << ", " << idx[2]
                                                                           << ") is degenerate or clockwise in uv "
                                                                              "(signed area "
                                                                           << 0.5 * twiceArea << " m^2)");
    // grad(phi_k) = perp(e_k) / (2 area), perp rotating by +90 degrees; area * g_a^T D g_b = perp_a^T D perp_b / (4A).
    Eigen::Vector2d g[3];
    for (int k = 0; k < 3; ++k) g[k] = Eigen::Vector2d(-e[k].y(), e[k].x());
    for (int a = 0; a < 3; ++a) {
      const int ra = role[idx[a]];
      if (ra < 0) continue;  // only interior rows are needed
      for (int b = 0; b < 3; ++b) {
        const double k = g[a].dot(D * g[b]) / (2.0 * twiceArea);
        const int rb = role[idx[b]];
        if (rb >= 0)
          kii.emplace_back(ra, rb, k);
        else
          kib.emplace_back(ra, -2 - rb, k);
      }
    }
  }
  basis_.resize(ni, nb);
  if (ni == 0) return;
  Eigen::SparseMatrix<double> Kii(ni, ni), Kib(ni, nb);
  Kii.setFromTriplets(kii.begin(), kii.end());
  Kib.setFromTriplets(kib.begin(), kib.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(Kii);
  PIXELCLOTH_CHECK(solver.info() == Eigen::Success,
                   "patch basis: the interior stiffness matrix is singular (an interior vertex without triangles, or "
                   "a part of the patch not connected to its boundary)");
  basis_ = -Eigen::MatrixXd(Kib);
  basis_ = solver.solve(basis_);
  PIXELCLOTH_CHECK(basis_.allFinite() && (solver.vectorD().array() > 0).all(),
                   "patch basis: the interior stiffness matrix is not positive definite (a part of the patch not "
                   "connected to its boundary?)");
}

void PatchBasis::checkValues(const Eigen::Ref<const Eigen::MatrixX3d>& boundaryValues) const {
  PIXELCLOTH_CHECK(boundaryValues.rows() == numBoundary(), "patch basis: expected " << numBoundary()
                                                                                    << " boundary values (one per "
                                                                                       "boundary vertex), got "
                                                                                    << boundaryValues.rows());
  PIXELCLOTH_CHECK(boundaryValues.allFinite(), "patch basis: the boundary values are not all finite");
}

Eigen::MatrixX3d PatchBasis::fill(const Eigen::Ref<const Eigen::MatrixX3d>& boundaryValues) const {
  checkValues(boundaryValues);
  Eigen::MatrixX3d result(numInterior(), 3);
  result.noalias() = basis_ * boundaryValues;
  return result;
}

Eigen::MatrixX3d PatchBasis::fillAll(const Eigen::Ref<const Eigen::MatrixX3d>& boundaryValues) const {
  Eigen::MatrixX3d inside = fill(boundaryValues);
  Eigen::MatrixX3d all(numVertices_, 3);
  for (int j = 0; j < numBoundary(); ++j) all.row(boundary_[j]) = boundaryValues.row(j);
  for (int i = 0; i < numInterior(); ++i) all.row(interior_[i]) = inside.row(i);
  return all;
}

Eigen::MatrixX3d fillPatch(const PatchMesh& patch, const Eigen::Ref<const Eigen::MatrixX3d>& boundaryValues,
                           const BasisOptions& options) {
  return PatchBasis(patch, options).fill(boundaryValues);
}

PatchMesh rectanglePatch(double width, double height, int nu, int nv) {
  PIXELCLOTH_CHECK(width > 0 && height > 0 && std::isfinite(width) && std::isfinite(height),
                   "rectangle patch: sizes must be positive, got " << width << " x " << height << " m");
  PIXELCLOTH_CHECK(nu >= 1 && nv >= 1, "rectangle patch: cell counts must be >= 1, got " << nu << " x " << nv);
  PatchMesh patch;
  const int gridCount = (nu + 1) * (nv + 1);
  auto grid = [nu](int i, int j) { return j * (nu + 1) + i; };
  patch.uv.resize(gridCount + nu * nv, 2);
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) patch.uv.row(grid(i, j)) << width * i / nu, height * j / nv;
  patch.F.resize(4 * nu * nv, 3);
  int f = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int c = gridCount + j * nu + i;
      patch.uv.row(c) << width * (i + 0.5) / nu, height * (j + 0.5) / nv;
      const int a = grid(i, j), b = grid(i + 1, j), d = grid(i + 1, j + 1), e = grid(i, j + 1);
      patch.F.row(f++) << a, b, c;
      patch.F.row(f++) << b, d, c;
      patch.F.row(f++) << d, e, c;
      patch.F.row(f++) << e, a, c;
    }
  for (int i = 0; i < nu; ++i) patch.boundary.push_back(grid(i, 0));
  for (int j = 0; j < nv; ++j) patch.boundary.push_back(grid(nu, j));
  for (int i = nu; i > 0; --i) patch.boundary.push_back(grid(i, nv));
  for (int j = nv; j > 0; --j) patch.boundary.push_back(grid(0, j));
  for (int j = 1; j < nv; ++j)
    for (int i = 1; i < nu; ++i) patch.interior.push_back(grid(i, j));
  for (int c = gridCount; c < gridCount + nu * nv; ++c) patch.interior.push_back(c);
  patch.globalVertex.resize(patch.uv.rows());
  for (int v = 0; v < patch.uv.rows(); ++v) patch.globalVertex[v] = v;
  return patch;
}

}  // namespace pixelcloth::patches
