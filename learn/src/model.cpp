// The paper's decoders and the fully connected baselines: one layer plan per architecture, from which both the
// LibTorch module and the summary (parameters, shapes, FLOPs) are made, so the two cannot disagree.
#include "pixelcloth/learn/model.h"

#include <ATen/CPUGeneratorImpl.h>
#include <torch/torch.h>

#include <cmath>

#include "layers.h"
#include "model_impl.h"
#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"
#include "tensor.h"

namespace pixelcloth::learn {

namespace {

const core::EnumNames<Architecture, 5> kArchitectures{"architecture",
                                                      {{{Architecture::Whole, "whole"},
                                                        {Architecture::Patch, "patch"},
                                                        {Architecture::Necktie, "necktie"},
                                                        {Architecture::FullyConnected, "fc"},
                                                        {Architecture::FullyConnectedPca, "fc-pca"}}}};

/// One step of a network: what it is, its sizes and the shape of one sample after it.
struct Layer {
  enum class Kind { Linear, Unflatten, ConvTranspose, Conv, BatchNorm, ReLU, PcaDecode } kind;
  std::int64_t in = 0, out = 0;  ///< features or channels
  std::int64_t kernel = 0, stride = 1, padding = 0;
  std::vector<std::int64_t> shape;  ///< one sample's output shape
};

/// A channel count scaled by the width multiplier, at least 1.
std::int64_t scaled(double channels, double width) { return std::max<std::int64_t>(1, std::llround(channels * width)); }

/// A decoder layer's channels: `nominal` scaled by the width, but at least `floor` (or `nominal` itself when that
/// is smaller).
std::int64_t decoderChannels(double nominal, double width, int floor) {
  return std::max(scaled(nominal, width), std::min<std::int64_t>(std::llround(nominal), floor));
}

/// Builds the plan of layers; `shape` tracks one sample's shape.
class Plan {
 public:
  Plan(std::int64_t inputs, int minChannels) : shape_{inputs}, minChannels_(minChannels) {}
  void linear(std::int64_t out) { add({Layer::Kind::Linear, shape_[0], out, 0, 1, 0, {out}}); }
  void unflatten(std::vector<std::int64_t> shape) { add({Layer::Kind::Unflatten, 0, 0, 0, 1, 0, std::move(shape)}); }
  void convTranspose(std::int64_t out, std::int64_t kernel, std::int64_t stride, std::int64_t padding) {
    const std::int64_t h = (shape_[1] - 1) * stride - 2 * padding + kernel,
                       w = (shape_[2] - 1) * stride - 2 * padding + kernel;
    add({Layer::Kind::ConvTranspose, shape_[0], out, kernel, stride, padding, {out, h, w}});
  }
  void conv(std::int64_t out, std::int64_t kernel) {
    add({Layer::Kind::Conv, shape_[0], out, kernel, 1, kernel / 2, {out, shape_[1], shape_[2]}});
  }
  void batchNormRelu() {
    add({Layer::Kind::BatchNorm, shape_[0], shape_[0], 0, 1, 0, shape_});
    add({Layer::Kind::ReLU, 0, 0, 0, 1, 0, shape_});
  }
  void relu() { add({Layer::Kind::ReLU, 0, 0, 0, 1, 0, shape_}); }
  void pcaDecode(std::int64_t values) { add({Layer::Kind::PcaDecode, shape_[0], values, 0, 1, 0, {values}}); }
  /// (4x4 stride-2 transposed convolution, BatchNorm, ReLU) blocks, channels halving from `nominal` (before the width
  /// multiplier), until the map is `height` rows high.
  void upsampleTo(std::int64_t height, double nominal, double width) {
    while (shape_[1] < height) {
      nominal /= 2;
      convTranspose(decoderChannels(nominal, width, minChannels_), 4, 2, 1);
      batchNormRelu();
    }
  }
  /// A linear layer to a rows x columns map of `nominal` channels, BatchNorm, ReLU, the upsampling blocks until the
  /// map is `height` rows high, and a 3x3 convolution to the 3 offset channels.
  void mapDecoder(std::int64_t rows, std::int64_t columns, double nominal, double width, std::int64_t height) {
    const std::int64_t c = decoderChannels(nominal, width, minChannels_);
    linear(rows * columns * c);
    unflatten({c, rows, columns});
    batchNormRelu();
    upsampleTo(height, nominal, width);
    conv(3, 3);
  }
  const std::vector<Layer>& layers() const { return layers_; }

 private:
  void add(Layer layer) {
    shape_ = layer.shape;
    layers_.push_back(std::move(layer));
  }
  std::vector<std::int64_t> shape_;
  int minChannels_ = 0;
  std::vector<Layer> layers_;
};

/// The appendix's networks, DESIGN.md "Networks".
std::vector<Layer> planOf(const ModelSpec& spec) {
  const double w = spec.width;
  Plan plan(spec.inputs(), spec.minChannels);
  switch (spec.architecture) {
    case Architecture::Whole: {  // 90 -> 8x8x384 -> ... -> 256x256x12 -> 6
      plan.unflatten({spec.inputs(), 1, 1});
      plan.convTranspose(decoderChannels(384, w, spec.minChannels), 8, 1, 0);
      plan.batchNormRelu();
      plan.upsampleTo(256, 384, w);
      plan.conv(6, 3);
      break;
    }
    case Architecture::Patch:  // 90 -> 5x5x512 -> ... -> 160x160x16 -> 3
      plan.mapDecoder(5, 5, 512, w, 160);
      break;
    case Architecture::Necktie:  // 36 -> 128 -> 32x8x64 -> ... -> 256x64x8 -> 3 (the tie hangs: 256 rows, 64 columns)
      plan.linear(scaled(128, w));
      plan.relu();
      plan.mapDecoder(32, 8, 64, w, 256);
      break;
    case Architecture::FullyConnected:
    case Architecture::FullyConnectedPca: {  // 2 x 256 ReLU -> values, or -> 128 coefficients -> PCA basis
      const std::int64_t hidden = scaled(256, w);
      plan.linear(hidden);
      plan.relu();
      plan.linear(hidden);
      plan.relu();
      if (spec.architecture == Architecture::FullyConnected) {
        plan.linear(spec.outputValues);
      } else {
        plan.linear(spec.pcaComponents);
        plan.pcaDecode(spec.outputValues);
      }
      break;
    }
  }
  return plan.layers();
}

LayerSummary summaryOf(const Layer& l, const std::vector<std::int64_t>& input) {
  LayerSummary s;
  s.output = l.shape;
  const std::string k = std::to_string(l.kernel) + "x" + std::to_string(l.kernel);
  switch (l.kind) {
    case Layer::Kind::Linear:
      s.name = "linear " + std::to_string(l.in) + "->" + std::to_string(l.out);
      s.parameters = l.in * l.out + l.out;
      s.flops = 2.0 * l.in * l.out;
      break;
    case Layer::Kind::Unflatten:
      s.name = "reshape";
      break;
    case Layer::Kind::ConvTranspose:
      s.name = "conv_transpose " + std::to_string(l.in) + "->" + std::to_string(l.out) + " " + k + " s" +
               std::to_string(l.stride);
      s.parameters = l.in * l.out * l.kernel * l.kernel + l.out;
      s.flops = 2.0 * l.in * l.out * l.kernel * l.kernel * input[1] * input[2];  // every input pixel scatters a kernel
      break;
    case Layer::Kind::Conv:
      s.name = "conv " + std::to_string(l.in) + "->" + std::to_string(l.out) + " " + k;
      s.parameters = l.in * l.out * l.kernel * l.kernel + l.out;
      s.flops = 2.0 * l.in * l.out * l.kernel * l.kernel * l.shape[1] * l.shape[2];
      break;
    case Layer::Kind::BatchNorm:
      s.name = "batch_norm " + std::to_string(l.out);
      s.parameters = 2 * l.out;
      s.flops = 2.0 * elementCount(l.shape);
      break;
    case Layer::Kind::ReLU:
      s.name = "relu";
      break;
    case Layer::Kind::PcaDecode:
      s.name = "pca_decode " + std::to_string(l.in) + "->" + std::to_string(l.out) + " (fixed basis)";
      s.flops = 2.0 * l.in * l.out;
      break;
  }
  return s;
}

/// LibTorch's default initialisation of Linear, Conv2d and ConvTranspose2d (weights and biases uniform in
/// +-1/sqrt(fan in), fan in from the weight's second dimension and kernel as LibTorch computes it), drawn from a
/// generator of `seed` of the network's own instead of LibTorch's global one: networks made on several threads at
/// once get the same weights as one at a time. Batch norms keep their ones and zeros; buffers are not parameters.
void initialiseParameters(torch::nn::Module& net, std::uint64_t seed) {
  torch::NoGradGuard noGrad;
  at::Generator generator = at::detail::createCPUGenerator(seed);
  for (const std::shared_ptr<torch::nn::Module>& module : net.modules(/*include_self=*/true)) {
    const auto own = module->named_parameters(/*recurse=*/false);
    const torch::Tensor* weight = own.find("weight");
    if (!weight || weight->dim() < 2) continue;
    const double fanIn = static_cast<double>(weight->numel() / weight->size(0));
    const double bound = 1.0 / std::sqrt(fanIn);
    weight->uniform_(-bound, bound, generator);
    if (const torch::Tensor* bias = own.find("bias")) bias->uniform_(-bound, bound, generator);
  }
}

torch::nn::Sequential buildNetwork(const std::vector<Layer>& layers) {
  torch::nn::Sequential net;
  for (const Layer& l : layers) {
    switch (l.kind) {
      case Layer::Kind::Linear:
        net->push_back(torch::nn::Linear(l.in, l.out));
        break;
      case Layer::Kind::Unflatten:
        net->push_back(torch::nn::Unflatten(torch::nn::UnflattenOptions(1, l.shape)));
        break;
      case Layer::Kind::ConvTranspose:
        net->push_back(TransposedConv2d(l.in, l.out, l.kernel, l.stride, l.padding));
        break;
      case Layer::Kind::Conv:
        net->push_back(ChannelsLastConv2d(l.in, l.out, l.kernel));
        break;
      case Layer::Kind::BatchNorm:
        net->push_back(torch::nn::BatchNorm2d(l.out));
        break;
      case Layer::Kind::ReLU:
        net->push_back(torch::nn::ReLU());
        break;
      case Layer::Kind::PcaDecode:
        net->push_back(PcaDecode(l.in, l.out));
        break;
    }
  }
  return net;
}

}  // namespace

const char* architectureName(Architecture architecture) { return kArchitectures.name(architecture); }

Architecture architectureFromName(const std::string& name, const std::string& context) {
  return kArchitectures.fromName(name, context);
}

void ModelSpec::validate() const {
  PIXELCLOTH_CHECK(std::isfinite(width) && width > 0 && width <= 4, "model: width " << width << ", expected (0, 4]");
  PIXELCLOTH_CHECK(inputSize >= 0 && inputSize <= 100000,
                   "model: input size " << inputSize << ", expected 0 to 100000");
  PIXELCLOTH_CHECK(minChannels >= 0 && minChannels <= 4096,
                   "model: minimum channels " << minChannels << ", expected 0 to 4096");
  const bool baseline = architecture == Architecture::FullyConnected || architecture == Architecture::FullyConnectedPca;
  PIXELCLOTH_CHECK(!baseline || outputValues > 0,
                   "model: the " << architectureName(architecture) << " baseline needs its output size (values per "
                                 << "sample, 3 per garment vertex), got " << outputValues);
  PIXELCLOTH_CHECK(
      architecture != Architecture::FullyConnectedPca || (pcaComponents >= 1 && pcaComponents <= outputValues),
      "model: " << pcaComponents << " PCA components for " << outputValues << " output values, expected 1 to "
                << outputValues);
}

int ModelSpec::inputs() const {
  if (inputSize > 0) return inputSize;
  return architecture == Architecture::Necktie ? body::kNecktiePoseSize : body::kPoseSize;
}

std::vector<std::int64_t> ModelSpec::outputShape() const {
  validate();
  return planOf(*this).back().shape;
}

nlohmann::json ModelSummary::toJson() const {
  nlohmann::json layerList = nlohmann::json::array();
  for (const LayerSummary& l : layers)
    layerList.push_back({{"name", l.name}, {"output", l.output}, {"parameters", l.parameters}, {"flops", l.flops}});
  return {{"architecture", architectureName(spec.architecture)},
          {"width", spec.width},
          {"min_channels", spec.minChannels},
          {"parameters", parameters},
          {"input", input},
          {"output", output},
          {"gflop_forward", gflopForward},
          {"layers", layerList}};
}

ModelSummary summarize(const ModelSpec& spec) {
  spec.validate();
  ModelSummary summary;
  summary.spec = spec;
  summary.input = {spec.inputs()};
  std::vector<std::int64_t> shape = summary.input;
  double flops = 0;
  for (const Layer& layer : planOf(spec)) {
    summary.layers.push_back(summaryOf(layer, shape));
    summary.parameters += summary.layers.back().parameters;
    flops += summary.layers.back().flops;
    shape = layer.shape;
  }
  summary.output = shape;
  summary.gflopForward = flops * 1e-9;
  return summary;
}

Model::Model(const ModelSpec& spec, std::uint64_t seed) : impl_(std::make_unique<Impl>()) {
  spec.validate();
  impl_->spec = spec;
  impl_->net = buildNetwork(planOf(spec));
  initialiseParameters(*impl_->net, seed);
  impl_->net->to(impl_->device);
}

Model::~Model() = default;
Model::Model(Model&&) noexcept = default;
Model& Model::operator=(Model&&) noexcept = default;

const ModelSpec& Model::spec() const { return impl_->spec; }

std::int64_t Model::parameters() const {
  std::int64_t n = 0;
  for (const torch::Tensor& p : impl_->net->parameters()) n += p.numel();
  return n;
}

Eigen::MatrixXf Model::forward(const Eigen::MatrixXf& inputs) const {
  PIXELCLOTH_CHECK(
      inputs.cols() == impl_->spec.inputs() && inputs.rows() > 0,
      "model: " << inputs.rows() << " x " << inputs.cols() << " inputs, expected batch x " << impl_->spec.inputs());
  PIXELCLOTH_CHECK(inputs.allFinite(), "model: the inputs are not all finite");
  torch::NoGradGuard noGrad;
  impl_->net->eval();
  return toEigen(impl_->net->forward(toTensor(inputs).to(impl_->device)));
}

void Model::setPcaBasis(const Eigen::VectorXf& mean, const Eigen::MatrixXf& components) {
  const ModelSpec& s = impl_->spec;
  PIXELCLOTH_CHECK(s.architecture == Architecture::FullyConnectedPca,
                   "model: a PCA basis is for fc-pca, not " << architectureName(s.architecture));
  PIXELCLOTH_CHECK(
      mean.size() == s.outputValues && components.rows() == s.pcaComponents && components.cols() == s.outputValues,
      "model: a PCA basis of " << components.rows() << " x " << components.cols() << " (mean " << mean.size()
                               << "), expected " << s.pcaComponents << " x " << s.outputValues);
  auto decode = impl_->net->ptr(impl_->net->size() - 1)->as<PcaDecodeImpl>();
  PIXELCLOTH_ASSERT(decode != nullptr, "fc-pca network without its PCA layer");
  torch::NoGradGuard noGrad;
  decode->mean.copy_(toTensor(mean.transpose()).reshape({-1}));
  decode->basis.copy_(toTensor(components));
}

}  // namespace pixelcloth::learn
