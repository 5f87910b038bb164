#pragma once

#include <Eigen/Core>
#include <vector>

#include "pixelcloth/patches/patch.h"

namespace pixelcloth::patches {

/// How a patch's interior follows its boundary (paper's appendix on blendshape bases): isotropic harmonic
/// interpolation, or anisotropic diffusion with the constant tensor D = R(theta) diag(1, ratio) R(theta)^T in
/// pattern space, so that the influence of a boundary vertex reaches further along `theta` than across it.
struct BasisOptions {
  bool anisotropic = false;  ///< false: D = identity (`theta` and `ratio` are ignored)
  double theta = 0.0;        ///< radians, pattern-space direction of the faster diffusion (0 = +u, pi/2 = +v)
  /// Diffusion across `theta` relative to along it, 0 < ratio <= 1 (1 is isotropic). The anisotropic problem is the
  /// isotropic one after stretching pattern space by 1 / sqrt(ratio) along `theta`, so the reach along `theta` grows
  /// roughly by 1 / sqrt(ratio) relative to the reach across (about 3.2 for ratio 0.1).
  double ratio = 1.0;

  /// Throws `InputError` unless `theta` is finite and 0 < `ratio` <= 1 (checked only when `anisotropic`).
  void validate() const;
  /// The 2 x 2 diffusion tensor D (identity when not `anisotropic`).
  Eigen::Matrix2d tensor() const;
};

/// Per-patch blendshape basis (paper's appendix): column j is the P1 finite-element (cotangent-weight) solution of
/// div(D grad u) = 0 on the patch in pattern space with u = 1 at boundary vertex j and u = 0 at the other boundary
/// vertices, sampled at the interior vertices. The stiffness matrix is K_ij = sum over triangles T of
/// area(T) grad(phi_i)^T D grad(phi_j); the basis is -K_II^-1 K_IB, factored once (sparse LDL^T of the interior
/// block) and stored dense, so filling a patch from boundary values is one matrix product.
///
/// Properties (tests/patches/basis_test.cpp): rows sum to 1 (constants are reproduced); boundary data that is a
/// linear function of (u, v) is reproduced exactly in the interior, for any constant D; the entries lie in [0, 1]
/// when the stiffness matrix is an M-matrix (isotropic: all cotangent weights non-negative, e.g. non-obtuse or
/// Delaunay triangles). Anisotropic: the stiffness is an M-matrix only if the mesh is Delaunay in the metric of
/// D^-1, so small negative weights appear near the boundary (measured down to -0.21 at ratio 0.1 and -0.10 at
/// ratio 0.3 on the T-shirt's patches): the fill can undershoot non-negative data slightly.
class PatchBasis {
 public:
  /// Builds the basis of `patch` (local uv in metres, ccw triangles, ordered boundary loop). Throws `InputError` for
  /// invalid options, an empty boundary, indices out of range, vertices that are neither boundary nor interior,
  /// or a degenerate or clockwise triangle (|signed area| <= 1e-12 * longest edge^2, or negative).
  PatchBasis(const PatchMesh& patch, const BasisOptions& options = {});

  /// Interior values from boundary values: `boundaryValues` is #boundary x 3 (rows in the order of
  /// `PatchMesh::boundary`, any unit, e.g. offsets in metres); returns #interior x 3 in the order of
  /// `PatchMesh::interior`. Throws `InputError` for a wrong row count or non-finite values.
  Eigen::MatrixX3d fill(const Eigen::Ref<const Eigen::MatrixX3d>& boundaryValues) const;

  /// As `fill`, but returns all #n x 3 local vertices (boundary rows copied, interior rows filled).
  Eigen::MatrixX3d fillAll(const Eigen::Ref<const Eigen::MatrixX3d>& boundaryValues) const;

  /// The dense basis, #interior x #boundary: entry (i, j) is the weight of boundary vertex j at interior vertex i.
  const Eigen::MatrixXd& matrix() const { return basis_; }

  int numBoundary() const { return static_cast<int>(boundary_.size()); }
  int numInterior() const { return static_cast<int>(interior_.size()); }
  int numVertices() const { return numVertices_; }
  const BasisOptions& options() const { return options_; }

 private:
  void checkValues(const Eigen::Ref<const Eigen::MatrixX3d>& boundaryValues) const;

  BasisOptions options_;
  std::vector<int> boundary_, interior_;
  int numVertices_ = 0;
  Eigen::MatrixXd basis_;
};

/// One-shot fill: builds the `PatchBasis` of `patch` and applies it. `boundaryValues` is #boundary x 3; returns
/// #interior x 3. Use `PatchBasis` when the same patch is filled more than once.
Eigen::MatrixX3d fillPatch(const PatchMesh& patch, const Eigen::Ref<const Eigen::MatrixX3d>& boundaryValues,
                           const BasisOptions& options = {});

/// A rectangular patch [0, width] x [0, height] (metres) meshed as a regular grid of nu x nv cells, each cell split
/// into four triangles around its centre (no obtuse angle when cells are square, so isotropic cotangent weights are
/// >= 0). The
/// boundary loop runs counter-clockwise from the corner (0, 0); `globalVertex` is the identity. Vertices:
/// (nu + 1)(nv + 1) grid points then nu * nv cell centres. Throws `InputError` for non-positive sizes or counts.
PatchMesh rectanglePatch(double width, double height, int nu, int nv);

}  // namespace pixelcloth::patches
