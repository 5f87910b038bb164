#pragma once

// The paper's losses as LibTorch functions (learn/-internal: LibTorch stays out of the public headers). Shapes: B
// samples, C channels, H x W pixels, V vertices, F faces, E edges.

#include <torch/torch.h>

#include "pixelcloth/learn/train.h"

namespace pixelcloth::learn {

/// The paper's image loss on the enlarged patch: the mean over masked pixels and channels of |p - t| (L1) or
/// (p - t)^2 (L2). `predicted`, `target` B x C x H x W; `mask` B x 1 x H x W (or broadcastable), 1 where the padded UV
/// mask holds cloth or padding, 0 on empty pixels. Zero when nothing is masked. The baselines' B x values outputs
/// take the same loss with a mask of ones.
torch::Tensor maskedImageLoss(const torch::Tensor& predicted, const torch::Tensor& target, const torch::Tensor& mask,
                              ImageLoss kind = ImageLoss::L1);

/// The sample operator on a batch of images: `sample` the sparse (or dense) V x (H W) matrix of
/// patches::SampleOperator for one layout, `image` B x C x H x W; returns B x V x C per-vertex values.
torch::Tensor sampleImage(const torch::Tensor& sample, const torch::Tensor& image);

/// World positions of offsets in their embedded frames (DESIGN.md "Offsets"): origin + du t + dv b + dn n. `offsets`
/// B x V x 3; each frame tensor V x 3 or B x V x 3.
torch::Tensor positionsFromOffsets(const torch::Tensor& offsets, const torch::Tensor& origin, const torch::Tensor& t,
                                   const torch::Tensor& b, const torch::Tensor& n);

/// Unit per-vertex normals (B x V x 3) of `positions` (B x V x 3) on `faces` (F x 3, int64): the sum of the faces'
/// area-weighted normals around each vertex, normalised (a vertex without faces gets the zero vector).
torch::Tensor vertexNormals(const torch::Tensor& positions, const torch::Tensor& faces);

/// The normal loss: the mean over vertices of 1 - cos(predicted normal, true normal), normals by vertexNormals.
torch::Tensor normalLoss(const torch::Tensor& predicted, const torch::Tensor& truth, const torch::Tensor& faces);

/// The necktie's edge-length loss: the mean over `edges` (E x 2, int64) of | |e_predicted| - |e_true| |.
torch::Tensor edgeLengthLoss(const torch::Tensor& predicted, const torch::Tensor& truth, const torch::Tensor& edges);

}  // namespace pixelcloth::learn
