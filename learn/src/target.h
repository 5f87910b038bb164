#pragma once

// What one network predicts (learn/-internal): the shape of its output, how a sample's per-vertex values become its
// training target and loss mask, and how an output goes back to per-vertex values of the vertices it covers.

#include <torch/torch.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "pixelcloth/garment/garment.h"
#include "pixelcloth/learn/model.h"
#include "pixelcloth/patches/cloth_image.h"
#include "pixelcloth/patches/patch.h"

namespace pixelcloth::learn {

class Target {
 public:
  virtual ~Target() = default;
  /// One sample's output: {C, H, W} for images, {values} for the baselines.
  const std::vector<std::int64_t>& shape() const { return shape_; }
  /// Loss weights, broadcastable to 1 x shape(): 1 on the padded UV mask of the (enlarged) patch, 0 on empty pixels.
  const torch::Tensor& mask() const { return mask_; }
  /// Garment vertices the output covers, ascending.
  const std::vector<int>& vertices() const { return vertices_; }
  /// The covered faces (F x 3, int64) and mesh edges (E x 2, int64), in indices into vertices(): the normal and
  /// edge-length losses' mesh.
  const torch::Tensor& faces() const { return faces_; }
  const torch::Tensor& edges() const { return edges_; }
  /// The target of one sample: its per-vertex values (#V x 3, every garment vertex) encoded as the output is.
  virtual torch::Tensor encode(const Eigen::MatrixXf& values) const = 0;
  /// Per-vertex values of outputs (B x shape()): B x vertices().size() x 3, differentiable.
  virtual torch::Tensor decode(const torch::Tensor& output) const = 0;
  /// Moves the mask, the mesh and the sample operators to `device` (encode() still makes CPU tensors).
  virtual void to(const torch::Device& device);

 protected:
  /// Fills faces_ and edges_ from garment faces whose corners are all in vertices_.
  void setMesh(const garment::Garment& garment, const std::vector<int>& garmentFaces);
  std::vector<std::int64_t> shape_;
  torch::Tensor mask_;
  std::vector<int> vertices_;
  torch::Tensor faces_, edges_;
};

/// The whole garment's cloth image (the T-shirt's 6 x 256 x 256, the necktie's 3 x 256 x 64).
std::unique_ptr<Target> wholeImageTarget(const garment::Garment& garment);
/// A patch decoder's crop: 160 x 160 of its layout's 512 x 512 image, the enlarged patch rasterised with 4 px of
/// padding (patches::enlargedPatchFaces).
std::unique_ptr<Target> patchCropTarget(const garment::Garment& garment, const patches::Patch& patch);
/// The baselines' per-vertex values, 3 per vertex.
std::unique_ptr<Target> vertexTarget(const garment::Garment& garment);

/// The target of a model of `architecture` on `garment` (`patch` for the patch decoders).
std::unique_ptr<Target> targetOf(Architecture architecture, const garment::Garment& garment,
                                 const patches::Patch* patch);

/// A sparse torch matrix of an Eigen one, keeping only `rows` (in that order).
torch::Tensor sparseRows(const Eigen::SparseMatrix<float, Eigen::RowMajor, int>& matrix, const std::vector<int>& rows,
                         const std::vector<float>& scale = {});

}  // namespace pixelcloth::learn
