#include "gan_networks.h"

#include <ATen/CPUGeneratorImpl.h>

#include <cmath>
#include <sstream>

#include "pixelcloth/core/error.h"

namespace pixelcloth::stitch {

namespace nn = torch::nn;

namespace {

constexpr std::int64_t kImageChannels = 6, kImageSize = 256;

using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// pix2pix's only kernel: 4x4, padding 1; convolutions of stride 1 or 2, transposed ones of stride 2.
nn::Conv2d conv(std::int64_t in, std::int64_t out, std::int64_t stride, bool bias) {
  return nn::Conv2d(nn::Conv2dOptions(in, out, 4).stride(stride).padding(1).bias(bias));
}
nn::ConvTranspose2d upConv(std::int64_t in, std::int64_t out, bool bias) {
  return nn::ConvTranspose2d(nn::ConvTranspose2dOptions(in, out, 4).stride(2).padding(1).bias(bias));
}
nn::LeakyReLU leaky() { return nn::LeakyReLU(nn::LeakyReLUOptions().negative_slope(0.2)); }

/// pix2pix's init_weights("normal", 0.02) on every layer of `module`, drawn from `generator` (the networks' own, not
/// LibTorch's global one).
void initialiseWeights(nn::Module& module, at::Generator& generator) {
  torch::NoGradGuard noGrad;
  module.apply([&](nn::Module& m) {
    if (auto* c = m.as<nn::Conv2d>()) {
      c->weight.normal_(0.0, 0.02, generator);
      if (c->bias.defined()) c->bias.zero_();
    } else if (auto* t = m.as<nn::ConvTranspose2d>()) {
      t->weight.normal_(0.0, 0.02, generator);
      if (t->bias.defined()) t->bias.zero_();
    } else if (auto* b = m.as<nn::BatchNorm2d>()) {
      b->weight.normal_(1.0, 0.02, generator);
      b->bias.zero_();
    }
  });
}

void record(std::vector<std::vector<std::int64_t>>* shapes, const torch::Tensor& t) {
  if (shapes) shapes->push_back(t.sizes().slice(1).vec());
}

UNetGenerator seededGenerator(double width, at::Generator& random) {
  UNetGenerator generator(width, random);
  initialiseWeights(*generator, random);
  torch::NoGradGuard noGrad;
  for (torch::Tensor& p : generator->up[0]->parameters()) p.zero_();  // an untrained blender is the identity
  return generator;
}

PatchDiscriminator seededDiscriminator(double width, at::Generator& random) {
  PatchDiscriminator discriminator(width);
  initialiseWeights(*discriminator, random);
  return discriminator;
}

torch::optim::AdamOptions adamOptions(double learningRate) {
  return torch::optim::AdamOptions(learningRate).betas({0.5, 0.999});
}

}  // namespace

std::int64_t ganChannels(double nominal, double width) {
  return std::max<std::int64_t>(1, std::llround(nominal * width));
}

torch::Tensor SeededDropoutImpl::forward(const torch::Tensor& x) {
  if (!is_training() || p == 0) return x;
  const torch::Tensor keep = torch::empty_like(x).bernoulli_(1 - p, random);
  return x * keep / (1 - p);
}

UNetGeneratorImpl::UNetGeneratorImpl(double width_, at::Generator random) : width(width_) {
  // e[i]: channels of the encoder's level i output (256 / 2^(i+1) pixels square).
  const double nominal[8] = {64, 128, 256, 512, 512, 512, 512, 512};
  std::int64_t e[8];
  for (int i = 0; i < 8; ++i) e[i] = ganChannels(nominal[i], width);
  for (int i = 0; i < 8; ++i) {
    nn::Sequential block;
    if (i > 0) block->push_back(leaky());
    block->push_back(conv(i == 0 ? kImageChannels : e[i - 1], e[i], 2, false));
    if (i > 0 && i < 7) block->push_back(nn::BatchNorm2d(e[i]));
    down.push_back(register_module("down" + std::to_string(i), block));
  }
  // up[i] undoes down[i]: from the level below (the innermost's own output, else it concatenated with the skip) to
  // level i - 1's channels; up[0] to the image's.
  for (int i = 0; i < 8; ++i) {
    nn::Sequential block;
    block->push_back(nn::ReLU());
    const std::int64_t in = i == 7 ? e[7] : 2 * e[i], out = i == 0 ? kImageChannels : e[i - 1];
    block->push_back(upConv(in, out, i == 0));
    if (i > 0) block->push_back(nn::BatchNorm2d(out));
    if (i >= 4 && i <= 6) block->push_back(SeededDropout(0.5, random));
    up.push_back(register_module("up" + std::to_string(i), block));
  }
  mean = register_buffer("mean", torch::zeros({1, kImageChannels, 1, 1}));
  scale = register_buffer("scale", torch::ones({1, kImageChannels, 1, 1}));
}

torch::Tensor UNetGeneratorImpl::normalise(const torch::Tensor& x) const { return (x - mean) / scale; }

torch::Tensor UNetGeneratorImpl::forward(const torch::Tensor& x, std::vector<std::vector<std::int64_t>>* shapes) {
  TORCH_CHECK(x.dim() == 4 && x.size(1) == kImageChannels && x.size(2) == kImageSize && x.size(3) == kImageSize,
              "the GAN generator takes B x 6 x 256 x 256 images, got ", x.sizes());
  std::vector<torch::Tensor> skips;
  torch::Tensor h = normalise(x);
  for (nn::Sequential& block : down) {
    h = block->forward(h);
    record(shapes, h);
    skips.push_back(h);
  }
  h = up[7]->forward(h);
  record(shapes, h);
  for (int i = 6; i >= 0; --i) {
    h = up[i]->forward(torch::cat({skips[i], h}, 1));
    record(shapes, h);
  }
  return x + h * scale;
}

PatchDiscriminatorImpl::PatchDiscriminatorImpl(double width) {
  const std::int64_t c[4] = {ganChannels(64, width), ganChannels(128, width), ganChannels(256, width),
                             ganChannels(512, width)};
  layers->push_back(conv(2 * kImageChannels, c[0], 2, true));
  layers->push_back(leaky());
  for (int i = 1; i < 4; ++i) {
    layers->push_back(conv(c[i - 1], c[i], i < 3 ? 2 : 1, false));
    layers->push_back(nn::BatchNorm2d(c[i]));
    layers->push_back(leaky());
  }
  layers->push_back(conv(c[3], 1, 1, true));
  register_module("layers", layers);
}

torch::Tensor PatchDiscriminatorImpl::forward(const torch::Tensor& pair,
                                              std::vector<std::vector<std::int64_t>>* shapes) {
  TORCH_CHECK(pair.dim() == 4 && pair.size(1) == 2 * kImageChannels, "the PatchGAN takes B x 12 x H x W, got ",
              pair.sizes());
  torch::Tensor h = pair;
  for (nn::AnyModule& layer : *layers) {
    h = layer.forward(h);
    if (layer.ptr()->as<nn::Conv2d>()) record(shapes, h);
  }
  return h;
}

std::int64_t parameterCount(const nn::Module& module) {
  std::int64_t count = 0;
  for (const torch::Tensor& p : module.parameters()) count += p.numel();
  return count;
}

GanNetworks::GanNetworks(double width, double learningRate, std::uint64_t seed)
    : random(at::detail::createCPUGenerator(seed)),
      generator(seededGenerator(width, random)),
      discriminator(seededDiscriminator(width, random)),
      generatorAdam(generator->parameters(), adamOptions(learningRate)),
      discriminatorAdam(discriminator->parameters(), adamOptions(learningRate)) {}

GanStepLosses GanNetworks::step(const torch::Tensor& x, const torch::Tensor& y, const torch::Tensor& mask,
                                double l1Weight) {
  TORCH_CHECK(x.sizes() == y.sizes() && mask.dim() == 3 && mask.sizes() == x.sizes().slice(1), "a GAN step on inputs ",
              x.sizes(), ", targets ", y.sizes(), " and mask ", mask.sizes());
  generator->train();
  discriminator->train();
  const torch::Tensor fake = generator->forward(x);
  const torch::Tensor xn = generator->normalise(x), yn = generator->normalise(y);
  auto bce = [](const torch::Tensor& logits, double label) {
    return torch::binary_cross_entropy_with_logits(logits, torch::full_like(logits, label));
  };

  discriminatorAdam.zero_grad();
  const torch::Tensor real = discriminator->forward(torch::cat({xn, yn}, 1));
  const torch::Tensor blended = discriminator->forward(torch::cat({xn, generator->normalise(fake.detach())}, 1));
  const torch::Tensor discriminatorLoss = 0.5 * (bce(real, 1.0) + bce(blended, 0.0));
  discriminatorLoss.backward();
  discriminatorAdam.step();

  generatorAdam.zero_grad();
  const torch::Tensor judged = discriminator->forward(torch::cat({xn, generator->normalise(fake)}, 1));
  const torch::Tensor adversarial = bce(judged, 1.0);
  const torch::Tensor l1 = (mask * (fake - y).abs()).sum() / (mask.sum() * x.size(0));
  (adversarial + l1Weight * l1).backward();
  generatorAdam.step();
  return {l1.item<double>(), adversarial.item<double>(), discriminatorLoss.item<double>()};
}

ClothTensors::ClothTensors(const garment::Garment& garment, const std::string& context) : imager_(garment) {
  std::ostringstream layouts;
  for (const std::string& name : imager_.layouts()) layouts << (layouts.tellp() > 0 ? ", " : "") << name;
  PIXELCLOTH_CHECK(imager_.layouts() == (std::vector<std::string>{"front", "back"}) && imager_.width() == kImageSize &&
                       imager_.height() == kImageSize,
                   context << ": the GAN blender takes the T-shirt's 6 x 256 x 256 cloth images (layouts front and "
                           << "back); the " << garment.name << "'s are " << imager_.width() << " x " << imager_.height()
                           << " with layouts " << layouts.str());
  blank_ = imager_.rasterize(Eigen::MatrixXf::Zero(imager_.numVertices(), 3));
  mask_ = torch::zeros({kImageChannels, kImageSize, kImageSize});
  for (int l = 0; l < 2; ++l) {
    const RowMajor mask = (blank_.layers[l].mask.array() > 0.5f).cast<float>().matrix();
    for (int c = 0; c < 3; ++c)
      std::copy(mask.data(), mask.data() + mask.size(), mask_.data_ptr<float>() + (3 * l + c) * mask.size());
  }
}

torch::Tensor ClothTensors::images(const std::vector<const Eigen::MatrixXf*>& values) const {
  const std::int64_t B = static_cast<std::int64_t>(values.size()), pixels = kImageSize * kImageSize;
  torch::Tensor out = torch::empty({B, kImageChannels, kImageSize, kImageSize});
  for (std::int64_t k = 0; k < B; ++k) {
    const patches::ClothImage image = imager_.rasterize(*values[k]);
    for (int l = 0; l < 2; ++l) {
      const patches::ClothLayer& layer = image.layers[l];
      const Eigen::MatrixXf* channels[3] = {&layer.du, &layer.dv, &layer.dn};
      for (int c = 0; c < 3; ++c)
        Eigen::Map<RowMajor>(out.data_ptr<float>() + (k * kImageChannels + 3 * l + c) * pixels, kImageSize,
                             kImageSize) = *channels[c];
    }
  }
  return out;
}

Eigen::MatrixXf ClothTensors::values(const torch::Tensor& image) const {
  PIXELCLOTH_ASSERT(
      image.dim() == 3 && image.size(0) == kImageChannels && image.size(1) == kImageSize && image.size(2) == kImageSize,
      "a cloth image tensor of " << image.sizes() << ", expected 6 x 256 x 256");
  const torch::Tensor c = image.to(torch::kCPU, torch::kFloat32).contiguous();
  const std::int64_t pixels = kImageSize * kImageSize;
  patches::ClothImage decoded = blank_;
  for (int l = 0; l < 2; ++l) {
    patches::ClothLayer& layer = decoded.layers[l];
    Eigen::MatrixXf* channels[3] = {&layer.du, &layer.dv, &layer.dn};
    for (int k = 0; k < 3; ++k)
      *channels[k] = Eigen::Map<const RowMajor>(c.data_ptr<float>() + (3 * l + k) * pixels, kImageSize, kImageSize);
  }
  return imager_.sample(decoded);
}

}  // namespace pixelcloth::stitch
