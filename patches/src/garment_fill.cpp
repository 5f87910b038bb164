#include "pixelcloth/patches/garment_fill.h"

#include "pixelcloth/core/error.h"

namespace pixelcloth::patches {

GarmentFill::GarmentFill(const garment::Garment& garment, std::vector<Patch> patches, const BasisOptions& options)
    : patches_(std::move(patches)), numVertices_(garment.mesh.numVertices()) {
  meshes_.reserve(patches_.size());
  bases_.reserve(patches_.size());
  for (const Patch& patch : patches_) {
    meshes_.push_back(patchMesh(garment, patch));
    bases_.emplace_back(meshes_.back(), options);
  }
}

void GarmentFill::fillPatch(int p, const Eigen::Ref<const Eigen::MatrixX3d>& values, Eigen::MatrixX3d& out) const {
  const PatchMesh& mesh = meshes_.at(p);
  Eigen::MatrixX3d boundary(mesh.boundary.size(), 3);
  for (size_t i = 0; i < mesh.boundary.size(); ++i) boundary.row(i) = values.row(mesh.globalVertex[mesh.boundary[i]]);
  Eigen::MatrixX3d interior = bases_[p].fill(boundary);
  for (size_t i = 0; i < mesh.interior.size(); ++i) out.row(mesh.globalVertex[mesh.interior[i]]) = interior.row(i);
}

Eigen::MatrixX3d GarmentFill::fill(const Eigen::Ref<const Eigen::MatrixX3d>& values) const {
  PIXELCLOTH_CHECK(values.rows() == numVertices_, "garment fill: " << values.rows() << " rows of values, expected one "
                                                                   << "per garment vertex (" << numVertices_ << ")");
  Eigen::MatrixX3d out = values;
  for (size_t p = 0; p < patches_.size(); ++p) fillPatch(static_cast<int>(p), values, out);
  return out;
}

}  // namespace pixelcloth::patches
