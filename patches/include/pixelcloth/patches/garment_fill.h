#pragma once

#include <Eigen/Core>
#include <vector>

#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/basis.h"
#include "pixelcloth/patches/patch.h"

namespace pixelcloth::patches {

/// The blendshape bases of every patch of a garment, built once (paper's appendix: the interior of each patch is
/// filled from its boundary, the cage). `fill` keeps the values of cage vertices (every patch-boundary vertex) and
/// replaces every patch's interior by its basis applied to that patch's boundary values: one small dense product per
/// patch.
class GarmentFill {
 public:
  /// `patches` from segmentPatches(garment, cage cuts); bases built with `options` (isotropic by default).
  GarmentFill(const garment::Garment& garment, std::vector<Patch> patches, const BasisOptions& options = {});

  /// `values` #V x 3 (per-vertex offsets or positions); only the values at patch-boundary vertices are read.
  /// Returns #V x 3 with every interior vertex filled. Throws InputError when the row count is not #V.
  Eigen::MatrixX3d fill(const Eigen::Ref<const Eigen::MatrixX3d>& values) const;

  /// Fills one patch's interior into `out` (#V x 3), reading its boundary from `values`.
  void fillPatch(int patch, const Eigen::Ref<const Eigen::MatrixX3d>& values, Eigen::MatrixX3d& out) const;

  const std::vector<Patch>& patches() const { return patches_; }
  const std::vector<PatchBasis>& bases() const { return bases_; }
  int numVertices() const { return numVertices_; }

 private:
  std::vector<Patch> patches_;
  std::vector<PatchMesh> meshes_;
  std::vector<PatchBasis> bases_;
  int numVertices_ = 0;
};

}  // namespace pixelcloth::patches
