// The oneDNN inference engine: a model's LibTorch layers folded into a short list of operations (inner products,
// transposed convolutions, convolutions, each with its ReLU), compiled per batch size into primitives whose weight
// layouts the kernels choose, run over the networks of a frame on all cores.
#include "pixelcloth/learn/inference.h"

#include <omp.h>
#include <torch/torch.h>

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <oneapi/dnnl/dnnl.hpp>
#include <thread>
#include <unordered_map>

#include "few_channel_conv.h"
#include "layers.h"
#include "model_impl.h"
#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::learn {

namespace {

const core::EnumNames<Engine, 2> kEngines{"engine", {{{Engine::LibTorch, "libtorch"}, {Engine::OneDnn, "onednn"}}}};

using Tag = dnnl::memory::format_tag;
using Dims = dnnl::memory::dims;
constexpr auto kF32 = dnnl::memory::data_type::f32;

std::vector<float> copyOf(const torch::Tensor& t) {
  const torch::Tensor c = t.detach().to(torch::kCPU, torch::kFloat32).contiguous();
  return std::vector<float>(c.data_ptr<float>(), c.data_ptr<float>() + c.numel());
}

/// One layer once BatchNorm is folded in: y = relu?(W x + b).
struct Op {
  enum class Kind { InnerProduct, Deconvolution, Convolution } kind;
  std::vector<std::int64_t> in, out;  ///< one sample's shape: {features} or {channels, height, width}
  std::int64_t kernel = 1, stride = 1, padding = 0;
  bool relu = false;
  /// InnerProduct: out x in; Deconvolution: LibTorch's in x out x k x k; Convolution: out x in x k x k.
  std::vector<float> weights;
  std::vector<float> bias;  ///< one per output feature or channel
  Op(Kind k, std::vector<std::int64_t> inShape, std::vector<std::int64_t> outShape)
      : kind(k), in(std::move(inShape)), out(std::move(outShape)) {}
  std::int64_t outChannels() const { return out[0]; }
};

/// Folds y = gamma (x - mean) / sqrt(var + eps) + beta into the op that made x.
void foldBatchNorm(Op& op, const torch::nn::BatchNorm2dImpl& bn) {
  const std::vector<float> gamma = copyOf(bn.weight), beta = copyOf(bn.bias), mean = copyOf(bn.running_mean),
                           var = copyOf(bn.running_var);
  const std::int64_t channels = static_cast<std::int64_t>(gamma.size());
  std::vector<float> scale(channels), shift(channels);
  for (std::int64_t c = 0; c < channels; ++c) {
    scale[c] = gamma[c] / std::sqrt(var[c] + static_cast<float>(bn.options.eps()));
    shift[c] = beta[c] - scale[c] * mean[c];
  }
  // Which channel each output feature belongs to, and where each output's weights are.
  const std::int64_t outputs = op.out[0];
  PIXELCLOTH_ASSERT(outputs % channels == 0, "batch norm of " << channels << " channels after " << outputs);
  const std::int64_t perChannel = outputs / channels;  // an inner product unflattened to channels x rows x columns
  if (op.kind == Op::Kind::Deconvolution) {          // in x out x k x k
    const std::int64_t k2 = op.kernel * op.kernel, in = op.in[0];
    for (std::int64_t i = 0; i < in; ++i)
      for (std::int64_t o = 0; o < outputs; ++o)
        for (std::int64_t t = 0; t < k2; ++t) op.weights[(i * outputs + o) * k2 + t] *= scale[o];
  } else {  // out x (everything else)
    const std::int64_t row = static_cast<std::int64_t>(op.weights.size()) / outputs;
    for (std::int64_t o = 0; o < outputs; ++o)
      for (std::int64_t t = 0; t < row; ++t) op.weights[o * row + t] *= scale[o / perChannel];
  }
  for (std::int64_t o = 0; o < outputs; ++o) op.bias[o] = scale[o / perChannel] * op.bias[o] + shift[o / perChannel];
}

/// The ops of a model's LibTorch network, in eval mode.
std::vector<Op> opsOf(const Model& model) {
  const torch::nn::Sequential& net = ModelAccess::network(model);
  std::vector<std::int64_t> shape{model.spec().inputs()};
  std::vector<Op> ops;
  // The BatchNorm after an inner product acts on its output unflattened; `ops.back().out` keeps the flat size.
  for (const std::shared_ptr<torch::nn::Module>& child : net->children()) {
    if (const auto* linear = child->as<torch::nn::LinearImpl>()) {
      Op op{Op::Kind::InnerProduct, {elementCount(shape)}, {linear->options.out_features()}};
      op.weights = copyOf(linear->weight);
      op.bias = copyOf(linear->bias);
      shape = op.out;
      ops.push_back(std::move(op));
    } else if (const auto* unflatten = child->as<torch::nn::UnflattenImpl>()) {
      shape = unflatten->options.sizes();
    } else if (const auto* deconv = child->as<TransposedConv2dImpl>();
               deconv && shape[1] == 1 && shape[2] == 1 && deconv->padding == 0) {
      // On a 1 x 1 input (the whole-garment decoder's first layer) it is an inner product to out x k x k, where
      // oneDNN's transposed convolution took 7 ms.
      const std::int64_t in = shape[0], out = deconv->out, k = deconv->kernel;
      Op op{Op::Kind::InnerProduct, {in}, {out * k * k}};
      const std::vector<float> w = copyOf(deconv->weight), b = copyOf(deconv->bias);  // in x out x k x k
      op.weights.resize(w.size());
      for (std::int64_t i = 0; i < in; ++i)
        for (std::int64_t o = 0; o < out * k * k; ++o) op.weights[o * in + i] = w[i * out * k * k + o];
      for (std::int64_t o = 0; o < out * k * k; ++o) op.bias.push_back(b[o / (k * k)]);
      shape = {out, k, k};
      ops.push_back(std::move(op));
    } else if (const auto* deconv = child->as<TransposedConv2dImpl>()) {
      Op op{Op::Kind::Deconvolution, shape, {}};
      op.kernel = deconv->kernel;
      op.stride = deconv->stride;
      op.padding = deconv->padding;
      op.out = {deconv->out, (shape[1] - 1) * op.stride - 2 * op.padding + op.kernel,
                (shape[2] - 1) * op.stride - 2 * op.padding + op.kernel};
      op.weights = copyOf(deconv->weight);
      op.bias = copyOf(deconv->bias);
      shape = op.out;
      ops.push_back(std::move(op));
    } else if (const auto* conv = child->as<ChannelsLastConv2dImpl>()) {
      Op op{Op::Kind::Convolution, shape, {}};
      op.kernel = conv->kernel;
      op.padding = conv->padding;
      op.out = {conv->out, shape[1] + 2 * op.padding - op.kernel + 1, shape[2] + 2 * op.padding - op.kernel + 1};
      op.weights = copyOf(conv->weight);
      op.bias = copyOf(conv->bias);
      shape = op.out;
      ops.push_back(std::move(op));
    } else if (const auto* bn = child->as<torch::nn::BatchNorm2dImpl>()) {
      PIXELCLOTH_ASSERT(!ops.empty() && !ops.back().relu, "batch norm without a layer before it");
      foldBatchNorm(ops.back(), *bn);
    } else if (child->as<torch::nn::ReLUImpl>()) {
      PIXELCLOTH_ASSERT(!ops.empty(), "ReLU without a layer before it");
      ops.back().relu = true;
    } else if (const auto* pca = child->as<PcaDecodeImpl>()) {  // mean + c B: an inner product with B^T
      Op op{Op::Kind::InnerProduct, {elementCount(shape)}, {pca->basis.size(1)}};
      op.weights = copyOf(pca->basis.t());
      op.bias = copyOf(pca->mean);
      shape = op.out;
      ops.push_back(std::move(op));
    } else {
      PIXELCLOTH_FAIL("the oneDNN engine has no layer " << child->name());
    }
  }
  return ops;
}

/// Where a step reads and writes: slot 0 is the network's input, 1 its output, 2 and on scratch activations.
struct Step {
  dnnl::primitive primitive;
  int op = -1;  ///< whose weights and bias it takes; -1 for reorders and ReLUs
  int src = 0, dst = 0;
  dnnl::memory::desc weights;  ///< the layout the kernel chose for them
  dnnl::memory::desc scratchpad;
  bool fewChannel = false;  ///< our own last-layer convolution (few_channel_conv.h) instead of a primitive
  int block = 0;            ///< its input's (or the interleave's) channel block
  int part = -1;            ///< 0-3: the output parity (row, column) of a transposed convolution's 2x2 part
  bool interleave = false;  ///< weaves the four parts (slots `parts`, each `shape`) into `dst`
  std::array<int, 4> parts{};
  Dims shape = {};
};

/// A 4x4 stride-2 transposed convolution (padding 1) is four 2x2 convolutions, one per output parity (ry, rx):
/// out[2m + ry][2n + rx] takes input rows m - 1, m (ry = 0) or m, m + 1 (ry = 1) with kernel rows kTaps[ry], and the
/// same for columns. oneDNN's convolutions are faster than its transposed convolutions at every layer of the
/// decoders (DESIGN.md, "Inference"; most where channels are few and maps large): 28 patch decoders 135 -> 111 ms a
/// frame at width 1, 91 -> 26 ms at width 0.25.
constexpr int kTaps[2][2] = {{3, 1}, {2, 0}};

/// Writes the four parity parts (each batch x blocks x height x width x block) into one map of twice the size in
/// the same layout.
void interleaveParts(const std::array<const float*, 4>& parts, float* out, std::int64_t batch, std::int64_t channels,
                     std::int64_t height, std::int64_t width, int block) {
  const std::int64_t blocks = (channels + block - 1) / block, rows = batch * blocks * height;
  const size_t bytes = sizeof(float) * static_cast<size_t>(block);
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < rows; ++r) {
    const std::int64_t map = r / height, h = r % height;
    for (int ry = 0; ry < 2; ++ry) {
      const float* left = parts[2 * ry] + (map * height + h) * width * block;
      const float* right = parts[2 * ry + 1] + (map * height + h) * width * block;
      float* row = out + (map * 2 * height + 2 * h + ry) * 2 * width * block;
      for (std::int64_t w = 0; w < width; ++w) {
        std::memcpy(row + 2 * w * block, left + w * block, bytes);
        std::memcpy(row + (2 * w + 1) * block, right + w * block, bytes);
      }
    }
  }
}

/// The primitives of one batch size, shared by every network (they share a spec); the weights are per network.
struct Program {
  std::int64_t batch = 0;
  std::vector<dnnl::memory::desc> slots;
  std::vector<Step> steps;
  size_t scratchpadBytes = 0;
};

/// One thread's activations and scratch space for a program.
struct Workspace {
  std::vector<dnnl::memory> slots;
  std::vector<dnnl::memory> scratchpads;  ///< one per step, all on `scratch`
  std::vector<char> scratch;
};

/// A network's folded ops and its weights in each layout a program asked for.
struct EngineNetwork {
  std::vector<Op> ops;
  std::vector<dnnl::memory> bias;
  /// Per op and part (index 5 op + part + 1; part -1 is the op's own weights).
  std::vector<std::vector<std::pair<dnnl::memory::desc, dnnl::memory>>> weights;
  std::vector<std::vector<float>> packed;  ///< per op: the few-channel convolution's weights, else empty
  std::vector<int> packedBlock;             ///< per op: the channel block they were packed for
};

/// A last 3x3 convolution to a few channels goes to fewChannelConvolution.
bool isFewChannel(const std::vector<Op>& ops, size_t i) {
  const Op& op = ops[i];
  return i + 1 == ops.size() && op.kind == Op::Kind::Convolution && op.kernel == 3 && op.padding == 1 &&
         op.stride == 1 && op.out[0] <= 8 && !op.relu;
}

dnnl::memory::desc plainDesc(const std::vector<std::int64_t>& shape, std::int64_t batch) {
  if (shape.size() == 1) return {{batch, shape[0]}, kF32, Tag::nc};
  return {{batch, shape[0], shape[1], shape[2]}, kF32, Tag::nchw};
}

}  // namespace

const char* engineName(Engine engine) { return kEngines.name(engine); }
Engine engineFromName(const std::string& name, const std::string& context) { return kEngines.fromName(name, context); }

struct CompiledNetworks::Impl {
  ModelSpec spec;
  int threads = 1;
  dnnl::engine engine{dnnl::engine::kind::cpu, 0};
  std::vector<EngineNetwork> networks;
  std::map<std::int64_t, Program> programs;                     ///< by batch size
  std::map<std::int64_t, std::vector<Workspace>> workspaces;    ///< by batch size, one per worker

  int workers() const { return static_cast<int>(networks.size()) >= threads ? threads : 1; }
  const Program& program(std::int64_t batch);
  const dnnl::memory& weightsOf(EngineNetwork& network, int op, int part, const dnnl::memory::desc& desc);
  /// `partsAtOnce`: how many of a transposed convolution's four parts run side by side (1: one after another).
  void run(const Program& program, Workspace& workspace, EngineNetwork& network, const float* input, float* output,
           int partsAtOnce);
  void execute(const Program& program, Workspace& workspace, EngineNetwork& network, size_t step, dnnl::stream& stream);
};

const Program& CompiledNetworks::Impl::program(std::int64_t batch) {
  auto found = programs.find(batch);
  if (found != programs.end()) return found->second;
  Program program;
  program.batch = batch;
  const std::vector<Op>& ops = networks.front().ops;
  program.slots = {plainDesc(ops.front().in, batch), plainDesc(ops.back().out, batch)};
  int current = 0;  // slot holding the next op's input
  dnnl::primitive_attr reluAttr, plainAttr;
  {
    dnnl::post_ops relu;
    relu.append_eltwise(1.0f, dnnl::algorithm::eltwise_relu, 0.0f, 0.0f);
    reluAttr.set_post_ops(relu);
  }
  for (dnnl::primitive_attr* attr : {&reluAttr, &plainAttr}) attr->set_scratchpad_mode(dnnl::scratchpad_mode::user);
  auto addSlot = [&](const dnnl::memory::desc& desc) {
    program.slots.push_back(desc);
    return static_cast<int>(program.slots.size()) - 1;
  };
  // Brings `current` into `desc`'s layout (a reorder step when they differ).
  auto bringTo = [&](const dnnl::memory::desc& desc) {
    if (program.slots[current] == desc) return;
    const int slot = addSlot(desc);
    dnnl::reorder::primitive_desc pd(engine, program.slots[current], engine, desc, plainAttr);
    program.steps.push_back({dnnl::reorder(pd), -1, current, slot, {}, pd.scratchpad_desc()});
    current = slot;
  };
  for (size_t i = 0; i < ops.size(); ++i) {
    const Op& op = ops[i];
    const bool last = i + 1 == ops.size();
    const dnnl::memory::desc bias({op.outChannels()}, kF32, Tag::x);
    if (op.kind == Op::Kind::InnerProduct) {
      // Its input is plain: nc, or a map in nchw, flattened as LibTorch flattens it.
      const Dims dims = program.slots[current].dims();
      if (dims.size() == 4) bringTo(dnnl::memory::desc(dims, kF32, Tag::nchw));
      const dnnl::memory::desc src({batch, op.in[0]}, kF32, Tag::nc), dst({batch, op.out[0]}, kF32, Tag::nc),
          weights({op.out[0], op.in[0]}, kF32, Tag::any);
      dnnl::inner_product_forward::primitive_desc pd(
          dnnl::inner_product_forward::desc(dnnl::prop_kind::forward_inference, src, weights, bias, dst),
          op.relu ? reluAttr : plainAttr, engine);
      if (program.slots[current] != src) program.slots[current] = src;  // the same plain bytes, seen as rows
      const int slot = last ? 1 : addSlot(pd.dst_desc());
      program.steps.push_back({dnnl::inner_product_forward(pd), static_cast<int>(i), current, slot, pd.weights_desc(),
                               pd.scratchpad_desc()});
      current = slot;
      continue;
    }
    // A convolution or transposed convolution on a {C, H, W} map; an inner product's nc output is that map in nchw.
    if (program.slots[current].dims().size() == 2) program.slots[current] = plainDesc(op.in, batch);
    if (isFewChannel(ops, i)) {
      // It reads the layout the layer before chose if that is one of channel blocks, else nhwc.
      const Dims dims{batch, op.in[0], op.in[1], op.in[2]};
      int block = 0;
      for (const auto& [tag, size] : {std::pair{Tag::nChw16c, 16}, {Tag::nChw8c, 8}, {Tag::nchw, 1}})
        if (program.slots[current] == dnnl::memory::desc(dims, kF32, tag)) block = size;
      if (block == 0) {
        bringTo(dnnl::memory::desc(dims, kF32, Tag::nhwc));
        block = static_cast<int>(op.in[0]);
      }
      Step step{dnnl::primitive(), static_cast<int>(i), current, 1, {}, {}};
      step.fewChannel = true;
      step.block = block;
      program.steps.push_back(step);
      current = 1;
      continue;
    }
    const Tag dstTag = last ? Tag::nchw : Tag::any;
    const Dims srcDims{batch, op.in[0], op.in[1], op.in[2]}, dstDims{batch, op.out[0], op.out[1], op.out[2]},
        weightDims{op.out[0], op.in[0], op.kernel, op.kernel}, strides{op.stride, op.stride},
        padding{op.padding, op.padding};
    const dnnl::memory::desc src(srcDims, kF32, Tag::any), weights(weightDims, kF32, Tag::any),
        dst(dstDims, kF32, dstTag);
    std::vector<dnnl::convolution_forward::primitive_desc> parityPds;
    Step weave{dnnl::primitive(), -1, -1, 0, {}, {}};
    dnnl::memory::desc partLayout;
    Tag tag = Tag::undef;
    bool parity = op.kind == Op::Kind::Deconvolution && op.kernel == 4 && op.stride == 2 && op.padding == 1 && !last;
    if (parity) {
      const Dims partDims{batch, op.out[0], op.in[1], op.in[2]};
      const dnnl::memory::desc partWeights({op.out[0], op.in[0], 2, 2}, kF32, Tag::any), partDst(partDims, kF32, Tag::any);
      std::vector<dnnl::convolution_forward::primitive_desc>& pds = parityPds;
      for (int part = 0; part < 4; ++part) {
        const int ry = part / 2, rx = part % 2;
        const Dims before{ry == 0 ? 1 : 0, rx == 0 ? 1 : 0}, after{ry == 0 ? 0 : 1, rx == 0 ? 0 : 1};
        pds.emplace_back(dnnl::convolution_forward::desc(
                             dnnl::prop_kind::forward_inference, dnnl::algorithm::convolution_direct,
                             part == 0 ? src : pds.front().src_desc(), partWeights, bias, partDst, {1, 1}, before, after),
                         op.relu ? reluAttr : plainAttr, engine);
      }
      weave.interleave = true;
      weave.shape = partDims;
      partLayout = pds.front().dst_desc();
      for (const auto& [t, size] : {std::pair{Tag::nChw16c, 16}, {Tag::nChw8c, 8}, {Tag::nchw, 1},
                                    {Tag::nhwc, static_cast<int>(op.out[0])}})
        if (partLayout == dnnl::memory::desc(partDims, kF32, t)) std::tie(tag, weave.block) = std::pair{t, size};
      parity = tag != Tag::undef;  // else the transposed convolution below
    }
    if (parity) {
      const std::vector<dnnl::convolution_forward::primitive_desc>& pds = parityPds;
      bringTo(pds.front().src_desc());
      for (int part = 0; part < 4; ++part) {
        PIXELCLOTH_ASSERT(pds[part].dst_desc() == partLayout && pds[part].src_desc() == pds.front().src_desc(),
                          "a transposed convolution's parts in different layouts");
        const int slot = addSlot(partLayout);
        Step step{dnnl::convolution_forward(pds[part]), static_cast<int>(i), current, slot, pds[part].weights_desc(),
                  pds[part].scratchpad_desc()};
        step.part = part;
        program.steps.push_back(step);
        weave.parts[part] = slot;
      }
      weave.dst = addSlot(dnnl::memory::desc({batch, op.out[0], op.out[1], op.out[2]}, kF32, tag));
      program.steps.push_back(weave);
      current = weave.dst;
    } else if (op.kind == Op::Kind::Deconvolution) {
      // oneDNN's transposed convolution is 3.6x slower with a fused ReLU (DESIGN.md, "Inference"): it gets a ReLU step
      // of its own.
      dnnl::deconvolution_forward::primitive_desc pd(
          dnnl::deconvolution_forward::desc(dnnl::prop_kind::forward_inference, dnnl::algorithm::deconvolution_direct,
                                            src, weights, bias, dst, strides, padding, padding),
          plainAttr, engine);
      bringTo(pd.src_desc());
      const int slot = last ? 1 : addSlot(pd.dst_desc());
      program.steps.push_back({dnnl::deconvolution_forward(pd), static_cast<int>(i), current, slot,
                               pd.weights_desc(), pd.scratchpad_desc()});
      current = slot;
      if (op.relu) {
        dnnl::eltwise_forward::primitive_desc relu(
            dnnl::eltwise_forward::desc(dnnl::prop_kind::forward_inference, dnnl::algorithm::eltwise_relu,
                                        pd.dst_desc(), 0.0f),
            plainAttr, engine);
        program.steps.push_back({dnnl::eltwise_forward(relu), -1, current, current, {}, relu.scratchpad_desc()});
      }
    } else {
      dnnl::convolution_forward::primitive_desc pd(
          dnnl::convolution_forward::desc(dnnl::prop_kind::forward_inference, dnnl::algorithm::convolution_direct,
                                          src, weights, bias, dst, strides, padding, padding),
          op.relu ? reluAttr : plainAttr, engine);
      bringTo(pd.src_desc());
      const int slot = last ? 1 : addSlot(pd.dst_desc());
      program.steps.push_back({dnnl::convolution_forward(pd), static_cast<int>(i), current, slot, pd.weights_desc(),
                               pd.scratchpad_desc()});
      current = slot;
    }
  }
  if (current != 1) bringTo(program.slots[1]);  // (only when the last op could not write the plain layout)
  PIXELCLOTH_ASSERT(current == 1 || program.steps.back().dst == 1, "the program does not end in its output");
  for (const Step& step : program.steps) program.scratchpadBytes = std::max(program.scratchpadBytes, step.scratchpad.get_size());

  // Every worker's activations; every network's weights in the chosen layouts.
  std::vector<Workspace>& spaces = workspaces[batch];
  for (int w = 0; w < workers(); ++w) {
    Workspace space;
    // The four parts of a transposed convolution may run at once (run()), each on scratch of its own.
    const size_t stride = (program.scratchpadBytes + 63) / 64 * 64;
    space.scratch.resize(std::max<size_t>(4 * stride, 64));
    for (size_t s = 0; s < program.slots.size(); ++s)
      space.slots.push_back(s < 2 ? dnnl::memory(program.slots[s], engine, DNNL_MEMORY_NONE)
                                  : dnnl::memory(program.slots[s], engine));
    for (const Step& step : program.steps)
      space.scratchpads.emplace_back(step.scratchpad, engine, space.scratch.data() + std::max(step.part, 0) * stride);
    spaces.push_back(std::move(space));
  }
  for (EngineNetwork& network : networks)
    for (const Step& step : program.steps)
      if (step.fewChannel && network.packedBlock[step.op] != step.block) {
        const Op& op = network.ops[step.op];
        network.packed[step.op] =
            fewChannelWeights(op.weights, static_cast<int>(op.out[0]), static_cast<int>(op.in[0]), step.block);
        network.packedBlock[step.op] = step.block;
      } else if (step.op >= 0 && !step.fewChannel) {
        weightsOf(network, step.op, step.part, step.weights);
      }
  return programs.emplace(batch, std::move(program)).first->second;
}

const dnnl::memory& CompiledNetworks::Impl::weightsOf(EngineNetwork& network, int op, int part,
                                                     const dnnl::memory::desc& desc) {
  std::vector<std::pair<dnnl::memory::desc, dnnl::memory>>& cached = network.weights[5 * op + part + 1];
  for (const auto& [d, memory] : cached)
    if (d == desc) return memory;
  const Op& o = network.ops[op];
  const float* data = o.weights.data();
  std::vector<float> partWeights;
  dnnl::memory::desc plain;
  if (part >= 0) {  // a 2x2 part of a 4x4 transposed convolution, out x in x 2 x 2
    const std::int64_t in = o.in[0], out = o.out[0];
    partWeights.resize(static_cast<size_t>(out * in * 4));
    for (std::int64_t co = 0; co < out; ++co)
      for (std::int64_t ci = 0; ci < in; ++ci)
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b)
            partWeights[((co * in + ci) * 2 + a) * 2 + b] =
                o.weights[((ci * out + co) * 4 + kTaps[part / 2][a]) * 4 + kTaps[part % 2][b]];
    data = partWeights.data();
    plain = dnnl::memory::desc({out, in, 2, 2}, kF32, Tag::oihw);
  } else if (o.kind == Op::Kind::InnerProduct) {
    plain = dnnl::memory::desc({o.out[0], o.in[0]}, kF32, Tag::oi);
  } else {  // LibTorch keeps a transposed convolution's in x out x k x k
    plain = dnnl::memory::desc({o.out[0], o.in[0], o.kernel, o.kernel}, kF32,
                               o.kind == Op::Kind::Deconvolution ? Tag::iohw : Tag::oihw);
  }
  dnnl::memory source(plain, engine, const_cast<float*>(data)), target(desc, engine);
  dnnl::stream stream(engine);
  dnnl::reorder(source, target).execute(stream, source, target);
  stream.wait();
  cached.push_back({desc, target});
  return cached.back().second;
}

void CompiledNetworks::Impl::run(const Program& program, Workspace& space, EngineNetwork& network, const float* input,
                                 float* output, int partsAtOnce) {
  dnnl::stream stream(engine);
  space.slots[0].set_data_handle(const_cast<float*>(input));
  space.slots[1].set_data_handle(output);
  for (size_t s = 0; s < program.steps.size(); ++s) {
    const Step& step = program.steps[s];
    if (step.interleave) {
      stream.wait();
      std::array<const float*, 4> parts;
      for (int p = 0; p < 4; ++p) parts[p] = static_cast<const float*>(space.slots[step.parts[p]].get_data_handle());
      interleaveParts(parts, static_cast<float*>(space.slots[step.dst].get_data_handle()), step.shape[0],
                      step.shape[1], step.shape[2], step.shape[3], step.block);
      continue;
    }
    if (step.fewChannel) {
      stream.wait();
      const Op& op = network.ops[step.op];
      fewChannelConvolution(static_cast<const float*>(space.slots[step.src].get_data_handle()), program.batch,
                            static_cast<int>(op.in[1]), static_cast<int>(op.in[2]), static_cast<int>(op.in[0]), step.block,
                            network.packed[step.op], op.bias, static_cast<int>(op.out[0]),
                            static_cast<float*>(space.slots[step.dst].get_data_handle()));
      continue;
    }
    if (step.part == 0 && partsAtOnce > 1) {
      // One network on several threads: its transposed convolution's four parts side by side, one thread each,
      // where each part alone on all threads keeps them less busy (the maps are small or the channels few).
      PIXELCLOTH_ASSERT(s + 3 < program.steps.size() && program.steps[s + 3].part == 3, "a part without its three others");
      stream.wait();
      std::exception_ptr failure;
#pragma omp parallel for num_threads(partsAtOnce) schedule(static, 1)
      for (int p = 0; p < 4; ++p) {
        try {
          dnnl::stream own(engine);
          execute(program, space, network, s + p, own);
          own.wait();
        } catch (...) {
#pragma omp critical
          failure = std::current_exception();
        }
      }
      if (failure) std::rethrow_exception(failure);
      s += 3;
      continue;
    }
    execute(program, space, network, s, stream);
  }
  stream.wait();
}

void CompiledNetworks::Impl::execute(const Program& program, Workspace& space, EngineNetwork& network, size_t s,
                                     dnnl::stream& stream) {
  const Step& step = program.steps[s];
  std::unordered_map<int, dnnl::memory> args{{DNNL_ARG_SRC, space.slots[step.src]},
                                             {DNNL_ARG_DST, space.slots[step.dst]},
                                             {DNNL_ARG_SCRATCHPAD, space.scratchpads[s]}};
  if (step.op >= 0) {
    args.insert({DNNL_ARG_WEIGHTS, weightsOf(network, step.op, step.part, step.weights)});
    args.insert({DNNL_ARG_BIAS, network.bias[step.op]});
  }
  step.primitive.execute(stream, args);
}

CompiledNetworks::CompiledNetworks(const std::vector<const Model*>& models, int threads)
    : impl_(std::make_unique<Impl>()) {
  PIXELCLOTH_CHECK(!models.empty(), "inference: no networks to compile");
  PIXELCLOTH_CHECK(threads >= 0 && threads <= 1024, "inference: " << threads << " threads, expected 0 to 1024");
  impl_->spec = models.front()->spec();
  impl_->threads = threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
  torch::NoGradGuard noGrad;
  for (const Model* model : models) {
    const ModelSpec& s = model->spec();
    PIXELCLOTH_CHECK(s.architecture == impl_->spec.architecture && s.width == impl_->spec.width &&
                         s.inputs() == impl_->spec.inputs() && s.outputValues == impl_->spec.outputValues &&
                         s.pcaComponents == impl_->spec.pcaComponents,
                     "inference: networks of different specs (" << architectureName(s.architecture) << " width "
                                                                << s.width << " vs "
                                                                << architectureName(impl_->spec.architecture)
                                                                << " width " << impl_->spec.width << ")");
    EngineNetwork network;
    network.ops = opsOf(*model);
    network.weights.resize(5 * network.ops.size());
    network.packed.resize(network.ops.size());
    network.packedBlock.assign(network.ops.size(), 0);
    for (Op& op : network.ops)
      network.bias.emplace_back(dnnl::memory::desc({op.outChannels()}, kF32, Tag::x), impl_->engine, op.bias.data());
    impl_->networks.push_back(std::move(network));
  }
}

CompiledNetworks::~CompiledNetworks() = default;
CompiledNetworks::CompiledNetworks(CompiledNetworks&&) noexcept = default;
CompiledNetworks& CompiledNetworks::operator=(CompiledNetworks&&) noexcept = default;

const ModelSpec& CompiledNetworks::spec() const { return impl_->spec; }
int CompiledNetworks::size() const { return static_cast<int>(impl_->networks.size()); }
int CompiledNetworks::threads() const { return impl_->threads; }

void CompiledNetworks::forward(const RowsF& inputs, std::vector<RowsF>& outputs) const {
  PIXELCLOTH_CHECK(inputs.cols() == impl_->spec.inputs() && inputs.rows() > 0,
                   "inference: " << inputs.rows() << " x " << inputs.cols() << " inputs, expected batch x "
                                 << impl_->spec.inputs());
  PIXELCLOTH_CHECK(inputs.allFinite(), "inference: the inputs are not all finite");
  const std::int64_t batch = inputs.rows();
  const Program& program = impl_->program(batch);
  std::vector<Workspace>& spaces = impl_->workspaces[batch];
  const std::int64_t values = elementCount(impl_->networks.front().ops.back().out);
  outputs.resize(impl_->networks.size());
  for (RowsF& o : outputs) o.resize(batch, values);
  const int workers = impl_->workers(), networks = size();
  auto work = [&](int w, int ompThreads) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(ompThreads);
    for (int n = w; n < networks; n += workers)
      impl_->run(program, spaces[w], impl_->networks[n], inputs.data(), outputs[n].data(), std::min(ompThreads, 4));
    omp_set_num_threads(before);
  };
  if (workers == 1) {
    work(0, impl_->threads);
    return;
  }
  std::vector<std::thread> pool;
  std::exception_ptr failure;
  std::mutex mutex;
  for (int w = 0; w < workers; ++w)
    pool.emplace_back([&, w] {
      try {
        work(w, 1);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        failure = std::current_exception();
      }
    });
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace pixelcloth::learn
