#include "layers.h"

namespace pixelcloth::learn {

namespace {

using torch::autograd::AutogradContext;
using torch::autograd::variable_list;

/// y = conv_transpose(x, w) + b as the input gradient of conv(., w); its backward: dx = conv(dy, w), dw = the
/// convolution's weight gradient for input dy and output gradient x.
struct TransposedConvolution : torch::autograd::Function<TransposedConvolution> {
  static torch::Tensor forward(AutogradContext* ctx, const torch::Tensor& x, const torch::Tensor& w,
                               const torch::Tensor& b, std::int64_t stride, std::int64_t padding) {
    const std::int64_t k = w.size(2);
    const torch::Tensor shape = torch::empty(
        {x.size(0), w.size(1), (x.size(2) - 1) * stride - 2 * padding + k, (x.size(3) - 1) * stride - 2 * padding + k},
        x.options());  // only its sizes are read
    torch::Tensor y = std::get<0>(at::convolution_backward(x.contiguous(), shape, w, c10::nullopt, {stride, stride},
                                                                 {padding, padding}, {1, 1}, false, {0, 0}, 1,
                                                                 {true, false, false}));
    ctx->save_for_backward({x, w});
    ctx->saved_data["stride"] = stride;
    ctx->saved_data["padding"] = padding;
    return y.add_(b.view({1, -1, 1, 1}));  // in place: a new map of this size costs more than the sum
  }
  static variable_list backward(AutogradContext* ctx, variable_list gradients) {
    const variable_list saved = ctx->get_saved_variables();
    const torch::Tensor &x = saved[0], &w = saved[1];
    const std::int64_t stride = ctx->saved_data["stride"].toInt(), padding = ctx->saved_data["padding"].toInt();
    const torch::Tensor dy = gradients[0].contiguous();
    const torch::Tensor dx = torch::conv2d(dy, w, {}, stride, padding);
    const torch::Tensor dw = std::get<1>(at::convolution_backward(x.contiguous(), dy, w, c10::nullopt, {stride, stride},
                                                                  {padding, padding}, {1, 1}, false, {0, 0}, 1,
                                                                  {false, true, false}));
    return {dx, dw, dy.sum({0, 2, 3}), torch::Tensor(), torch::Tensor()};
  }
};

}  // namespace

TransposedConv2dImpl::TransposedConv2dImpl(std::int64_t in_, std::int64_t out_, std::int64_t kernel_,
                                           std::int64_t stride_, std::int64_t padding_)
    : in(in_), out(out_), kernel(kernel_), stride(stride_), padding(padding_) {
  // LibTorch's own layer draws the initial weights, so a seed gives the same network as before.
  torch::nn::ConvTranspose2d reference(
      torch::nn::ConvTranspose2dOptions(in, out, kernel).stride(stride).padding(padding));
  weight = register_parameter("weight", reference->weight.detach().clone());
  bias = register_parameter("bias", reference->bias.detach().clone());
}

torch::Tensor TransposedConv2dImpl::forward(const torch::Tensor& x) {
  return TransposedConvolution::apply(x, weight, bias, stride, padding);
}

ChannelsLastConv2dImpl::ChannelsLastConv2dImpl(std::int64_t in_, std::int64_t out_, std::int64_t kernel_)
    : in(in_), out(out_), kernel(kernel_), padding(kernel_ / 2) {
  torch::nn::Conv2d reference(torch::nn::Conv2dOptions(in, out, kernel).padding(padding));
  weight = register_parameter("weight", reference->weight.detach().clone());
  bias = register_parameter("bias", reference->bias.detach().clone());
}

torch::Tensor ChannelsLastConv2dImpl::forward(const torch::Tensor& x) {
  return torch::conv2d(x.contiguous(at::MemoryFormat::ChannelsLast), weight, bias, 1, padding).contiguous();
}

}  // namespace pixelcloth::learn
