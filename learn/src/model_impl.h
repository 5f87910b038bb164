#pragma once

// What learn/'s training and checkpoint code see of a Model (learn/-internal).

#include <torch/torch.h>

#include "pixelcloth/learn/model.h"

namespace pixelcloth::learn {

/// The number of elements of a tensor of `shape`.
inline std::int64_t elementCount(const std::vector<std::int64_t>& shape) {
  std::int64_t n = 1;
  for (std::int64_t d : shape) n *= d;
  return n;
}

/// Where models run: the GPU when this LibTorch build has CUDA and one is present (Debian's is CPU-only), else the CPU.
inline torch::Device defaultDevice() { return torch::cuda::is_available() ? torch::kCUDA : torch::kCPU; }

/// mean + coefficients x components, a fixed (non-trainable) basis.
struct PcaDecodeImpl : torch::nn::Module {
  PcaDecodeImpl(std::int64_t components, std::int64_t values) {
    mean = register_buffer("mean", torch::zeros({values}));
    basis = register_buffer("components", torch::zeros({components, values}));
  }
  torch::Tensor forward(const torch::Tensor& coefficients) { return mean + coefficients.matmul(basis); }
  torch::Tensor mean, basis;
};
TORCH_MODULE(PcaDecode);

struct Model::Impl {
  ModelSpec spec;
  torch::nn::Sequential net;
  torch::Device device{defaultDevice()};
};

/// The LibTorch network of a model, for training and checkpoints.
struct ModelAccess {
  static torch::nn::Sequential& network(Model& model) { return model.impl_->net; }
  static const torch::nn::Sequential& network(const Model& model) { return model.impl_->net; }
  static torch::Device device(const Model& model) { return model.impl_->device; }
};

}  // namespace pixelcloth::learn
