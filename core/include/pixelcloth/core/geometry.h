#pragma once

// Geometry that every stage shares, written once: triangle areas, area ratios against the pattern, the cotangent
// Laplacian and the lumped mass.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "pixelcloth/core/mesh.h"

namespace pixelcloth::core {

/// Per-face areas (#F) of triangles F (#F x 3) over vertices `V` (#V x 2 or #V x 3), square metres.
Eigen::VectorXd triangleAreas(const Eigen::Ref<const Eigen::MatrixXd>& V, const Eigen::MatrixX3i& F);

/// Per face (#F): the 3D area of the triangle in `positions` (#V x 3, rows of `pattern.V`'s vertices) over its area in
/// pattern space (`pattern.UV` through `pattern.FUV`). A triangle whose pattern area is zero gets 1. Throws InputError
/// when the sizes disagree or the pattern has no UVs.
Eigen::VectorXd areaRatios(const Eigen::MatrixX3d& positions, const Mesh& pattern);

/// Cotangent Laplacian (#n x #n, negative semi-definite, libigl's convention): off the diagonal
/// L_ij = (cot a_ij + cot b_ij) / 2 summed over the triangles at edge ij, rows summing to 0. Triangle f joins vertices
/// F(f, :) (in [0, n)) and has its corners at rows P(FP(f, :)) of `P` (#P x 2 or #P x 3): FP = F for a mesh's own
/// positions, FP = FUV for its flat pattern (a seam vertex has one position per layout). A degenerate triangle
/// (|e1 x e2| <= 1e-20) adds nothing.
Eigen::SparseMatrix<double> cotangentLaplacian(const Eigen::Ref<const Eigen::MatrixXd>& P, const Eigen::MatrixX3i& FP,
                                               const Eigen::MatrixX3i& F, int n);
/// The same on a mesh's own positions: `V` #V x 2 or 3, `F` #F x 3.
Eigen::SparseMatrix<double> cotangentLaplacian(const Eigen::Ref<const Eigen::MatrixXd>& V, const Eigen::MatrixX3i& F);

/// Lumped (barycentric) mass: a third of the area of each triangle at each of its corners (#V), square metres.
Eigen::VectorXd lumpedMass(const Eigen::Ref<const Eigen::MatrixXd>& V, const Eigen::MatrixX3i& F);

}  // namespace pixelcloth::core
