#pragma once

// What learn/'s training and checkpoint code see of a Model (learn/-internal).

#include <torch/torch.h>

#include "pixelcloth/learn/model.h"

namespace pixelcloth::learn {

struct Model::Impl {
  ModelSpec spec;
  torch::nn::Sequential net;
  torch::Device device{torch::kCPU};
};

/// The LibTorch network of a model, for training and checkpoints.
struct ModelAccess {
  static torch::nn::Sequential& network(Model& model) { return model.impl_->net; }
  static const torch::nn::Sequential& network(const Model& model) { return model.impl_->net; }
};

}  // namespace pixelcloth::learn
