#include "losses.h"

namespace pixelcloth::learn {

torch::Tensor maskedImageLoss(const torch::Tensor& predicted, const torch::Tensor& target, const torch::Tensor& mask,
                              ImageLoss kind) {
  TORCH_CHECK(predicted.sizes() == target.sizes(), "image loss: predicted ", predicted.sizes(), " but target ",
              target.sizes());
  TORCH_CHECK(predicted.dim() >= 2, "image loss: expected B x ... outputs, got ", predicted.sizes());
  const torch::Tensor difference = predicted - target;
  const torch::Tensor error = kind == ImageLoss::L1 ? difference.abs() : difference.square();
  const torch::Tensor weights = mask.to(predicted.dtype()).expand_as(predicted);
  return (error * weights).sum() / weights.sum().clamp_min(1.0);
}

torch::Tensor sampleImage(const torch::Tensor& sample, const torch::Tensor& image) {
  TORCH_CHECK(image.dim() == 4, "sample: expected B x C x H x W images, got ", image.sizes());
  const std::int64_t B = image.size(0), C = image.size(1), pixels = image.size(2) * image.size(3);
  TORCH_CHECK(sample.dim() == 2 && sample.size(1) == pixels, "sample: a ", sample.sizes(), " operator for ", pixels,
              " pixels");
  // (H W) x (B C): one column per sample and channel, so one sparse product serves the batch.
  const torch::Tensor columns = image.reshape({B * C, pixels}).t();
  const torch::Tensor values = sample.is_sparse() ? torch::mm(sample, columns) : sample.mm(columns);
  return values.t().reshape({B, C, -1}).permute({0, 2, 1});
}

torch::Tensor positionsFromOffsets(const torch::Tensor& offsets, const torch::Tensor& origin, const torch::Tensor& t,
                                   const torch::Tensor& b, const torch::Tensor& n) {
  TORCH_CHECK(offsets.dim() == 3 && offsets.size(2) == 3, "positions: expected B x V x 3 offsets, got ",
              offsets.sizes());
  using torch::indexing::Slice;
  return origin + offsets.index({Slice(), Slice(), Slice(0, 1)}) * t +
         offsets.index({Slice(), Slice(), Slice(1, 2)}) * b + offsets.index({Slice(), Slice(), Slice(2, 3)}) * n;
}

torch::Tensor vertexNormals(const torch::Tensor& positions, const torch::Tensor& faces) {
  TORCH_CHECK(positions.dim() == 3 && positions.size(2) == 3, "normals: expected B x V x 3 positions, got ",
              positions.sizes());
  TORCH_CHECK(faces.dim() == 2 && faces.size(1) == 3, "normals: expected F x 3 faces, got ", faces.sizes());
  const torch::Tensor p0 = positions.index_select(1, faces.select(1, 0)),
                      p1 = positions.index_select(1, faces.select(1, 1)),
                      p2 = positions.index_select(1, faces.select(1, 2));
  const torch::Tensor faceNormals = torch::cross(p1 - p0, p2 - p0, 2);  // length: twice the area
  torch::Tensor sum = torch::zeros_like(positions);
  for (int k = 0; k < 3; ++k) sum = sum.index_add(1, faces.select(1, k), faceNormals);
  return sum / sum.norm(2, 2, true).clamp_min(1e-12);
}

torch::Tensor normalLoss(const torch::Tensor& predicted, const torch::Tensor& truth, const torch::Tensor& faces) {
  const torch::Tensor cosine = (vertexNormals(predicted, faces) * vertexNormals(truth, faces)).sum(2);
  return (1 - cosine).mean();
}

torch::Tensor edgeLengthLoss(const torch::Tensor& predicted, const torch::Tensor& truth, const torch::Tensor& edges) {
  TORCH_CHECK(edges.dim() == 2 && edges.size(1) == 2, "edge lengths: expected E x 2 edges, got ", edges.sizes());
  auto lengths = [&](const torch::Tensor& x) {
    return (x.index_select(1, edges.select(1, 0)) - x.index_select(1, edges.select(1, 1))).norm(2, 2);
  };
  return (lengths(predicted) - lengths(truth)).abs().mean();
}

}  // namespace pixelcloth::learn
