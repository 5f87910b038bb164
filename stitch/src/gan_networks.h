#pragma once

// The GAN blender's networks and its training step (stitch/-internal; gan.h is the public side): pix2pix's U-Net
// generator (Isola et al. 2017, "unet_256") and 70 x 70 PatchGAN discriminator, with whole-garment cloth images as
// tensors.

#include <ATen/CPUGeneratorImpl.h>
#include <torch/torch.h>

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/cloth_image.h"

namespace pixelcloth::stitch {

/// A channel count of pix2pix (`nominal`, at width 1) scaled by the width multiplier, rounded, at least 1.
std::int64_t ganChannels(double nominal, double width);

/// The U-Net of pix2pix for 6 x 256 x 256 cloth images: eight 4x4 stride-2 convolutions (64, 128, 256, 512, 512, 512,
/// 512, 512 channels times the width; LeakyReLU 0.2, BatchNorm but on the first and the innermost), eight 4x4 stride-2
/// transposed convolutions back (ReLU, BatchNorm, dropout 0.5 on the three after the innermost), each level's encoder
/// output concatenated to its decoder input. Unlike pix2pix's (tanh image out), it predicts a residual: the output is
/// the input plus the last layer's image, in the input's per-channel scale, and that last layer starts at zero, so an
/// untrained generator is the identity. Convolutions have no bias where BatchNorm follows (as pix2pix).
/// Dropout (training only) whose masks are drawn from `random`, a generator shared with the networks it belongs to, so
/// that a seed fixes the training run without LibTorch's global generator.
struct SeededDropoutImpl : torch::nn::Module {
  SeededDropoutImpl(double p, at::Generator random) : p(p), random(std::move(random)) {}
  torch::Tensor forward(const torch::Tensor& x);
  double p;
  at::Generator random;
};
TORCH_MODULE(SeededDropout);

struct UNetGeneratorImpl : torch::nn::Module {
  /// `random` draws the dropout masks (a copy shares its state).
  explicit UNetGeneratorImpl(double width, at::Generator random = at::detail::createCPUGenerator());
  /// `x`: B x 6 x 256 x 256 offsets (metres) -> the same. When `shapes` is given, each layer's output shape (one
  /// sample) is appended to it, encoder first.
  torch::Tensor forward(const torch::Tensor& x, std::vector<std::vector<std::int64_t>>* shapes = nullptr);
  /// (x - mean) / scale per channel: what both networks see.
  torch::Tensor normalise(const torch::Tensor& x) const;

  double width;
  std::vector<torch::nn::Sequential> down, up;  ///< 8 each; up[0] is the outermost (to the 6 output channels)
  torch::Tensor mean, scale;                    ///< buffers, 1 x 6 x 1 x 1: the train split's input statistics
};
TORCH_MODULE(UNetGenerator);

/// pix2pix's 70 x 70 PatchGAN (n_layers 3) on the input and a candidate output side by side (12 channels, both
/// normalised by the generator's statistics): 4x4 convolutions of 64, 128, 256 (stride 2) and 512 (stride 1) channels
/// times the width, LeakyReLU 0.2, BatchNorm but on the first, then one to a 1 x 30 x 30 map of logits, each judging a
/// 70 x 70 pixel window as real or blended.
struct PatchDiscriminatorImpl : torch::nn::Module {
  explicit PatchDiscriminatorImpl(double width);
  /// `pair`: B x 12 x 256 x 256 -> B x 1 x 30 x 30 logits; each layer's output shape appended to `shapes` if given.
  torch::Tensor forward(const torch::Tensor& pair, std::vector<std::vector<std::int64_t>>* shapes = nullptr);
  torch::nn::Sequential layers;
};
TORCH_MODULE(PatchDiscriminator);

/// Trainable parameters of a module.
std::int64_t parameterCount(const torch::nn::Module& module);

/// Each loss of one training step.
struct GanStepLosses {
  double l1 = 0;             ///< masked mean |G(x) - y|, metres (before its weight)
  double adversarial = 0;    ///< the generator's BCE-with-logits against "real"
  double discriminator = 0;  ///< half the sum of the discriminator's BCE on real and on blended pairs
};

/// Both networks and their Adam optimisers (betas 0.5, 0.999), initialised from a seed as pix2pix does (convolution
/// weights N(0, 0.02), BatchNorm scales N(1, 0.02), biases 0), the generator's last layer at zero.
class GanNetworks {
 public:
  GanNetworks(double width, double learningRate, std::uint64_t seed);
  /// One pix2pix step on a batch: the discriminator on (x, y) as real and (x, G(x)) as blended, then the generator on
  /// adversarial + l1Weight * masked L1. `x`, `y`: B x 6 x 256 x 256 (metres); `mask`: 6 x 256 x 256, 1 where the L1
  /// counts (the padded UV mask), 0 elsewhere.
  GanStepLosses step(const torch::Tensor& x, const torch::Tensor& y, const torch::Tensor& mask, double l1Weight);

  at::Generator random;  ///< the initial weights' draws (the seed's; not LibTorch's global generator)
  UNetGenerator generator;
  PatchDiscriminator discriminator;
  torch::optim::Adam generatorAdam, discriminatorAdam;
};

/// Whole-garment cloth images of one T-shirt as tensors: 6 x 256 x 256, channels front du dv dn, back du dv dn.
class ClothTensors {
 public:
  /// Throws InputError unless `garment` has the T-shirt's two layouts (`context` names what asked).
  ClothTensors(const garment::Garment& garment, const std::string& context);
  /// `values`: each #V x 3, per-vertex (du, dv, dn) or values of another space -> B x 6 x 256 x 256.
  torch::Tensor images(const std::vector<const Eigen::MatrixXf*>& values) const;
  /// One image (6 x 256 x 256) back to #V x 3 values: the imager's bilinear sample, seam vertices averaged.
  Eigen::MatrixXf values(const torch::Tensor& image) const;
  /// 6 x 256 x 256: 1 on the padded UV mask (inside and padding), 0 on empty pixels.
  const torch::Tensor& mask() const { return mask_; }
  const patches::ClothImager& imager() const { return imager_; }

 private:
  patches::ClothImager imager_;
  patches::ClothImage blank_;
  torch::Tensor mask_;
};

}  // namespace pixelcloth::stitch
