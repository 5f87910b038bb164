#pragma once

// Two of LibTorch's layers with the same parameters (names, shapes, initialisation, so checkpoints are unchanged),
// computed the way LibTorch 1.13 is fast at on the CPU (learn/-internal; both were measured).

#include <torch/torch.h>

namespace pixelcloth::learn {

/// ConvTranspose2d (no groups, dilation or output padding). Computed as the input gradient of the convolution whose
/// weight it shares, and differentiated as that convolution (forward) and its weight gradient: all three go
/// through oneDNN, where LibTorch's own transposed convolution takes an im2col path forward and backward (0.88 ->
/// 0.55 s for the patch decoder's five at batch 32 on 2 cores).
struct TransposedConv2dImpl : torch::nn::Module {
  TransposedConv2dImpl(std::int64_t in, std::int64_t out, std::int64_t kernel, std::int64_t stride,
                       std::int64_t padding);
  torch::Tensor forward(const torch::Tensor& x);
  std::int64_t in, out, kernel, stride, padding;
  torch::Tensor weight, bias;  ///< in x out x kernel x kernel, as ConvTranspose2d's
};
TORCH_MODULE(TransposedConv2d);

/// Conv2d with "same" padding (stride 1), run on channels-last data: oneDNN's kernels for few output channels (the
/// decoders' last layer, 16 -> 3) are 2.2x faster so, forward and backward. The output is back in LibTorch's
/// default layout.
struct ChannelsLastConv2dImpl : torch::nn::Module {
  ChannelsLastConv2dImpl(std::int64_t in, std::int64_t out, std::int64_t kernel);
  torch::Tensor forward(const torch::Tensor& x);
  std::int64_t in, out, kernel, padding;
  torch::Tensor weight, bias;  ///< out x in x kernel x kernel, as Conv2d's
};
TORCH_MODULE(ChannelsLastConv2d);

}  // namespace pixelcloth::learn
