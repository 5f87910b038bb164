// The faster layers against LibTorch's own: the same initial parameters under a seed, the same outputs and the same
// gradients.
#include "layers.h"

#include <gtest/gtest.h>

namespace pl = pixelcloth::learn;

namespace {
/// max |a - b| over max |b|.
double relative(const torch::Tensor& a, const torch::Tensor& b) {
  return (a - b).abs().max().item<double>() / b.abs().max().item<double>();
}
}  // namespace

TEST(Layers, TransposedConvolutionIsLibTorchs) {
  for (auto [in, out, kernel, stride, padding, size] :
       {std::tuple{8, 4, 4, 2, 1, 5}, {6, 3, 8, 1, 0, 1}, {5, 7, 4, 2, 1, 10}}) {
    SCOPED_TRACE(std::to_string(in) + "->" + std::to_string(out) + " kernel " + std::to_string(kernel));
    torch::manual_seed(4);
    pl::TransposedConv2d fast(in, out, kernel, stride, padding);
    torch::manual_seed(4);
    torch::nn::ConvTranspose2d reference(
        torch::nn::ConvTranspose2dOptions(in, out, kernel).stride(stride).padding(padding));
    EXPECT_TRUE(torch::equal(fast->weight, reference->weight));
    EXPECT_TRUE(torch::equal(fast->bias, reference->bias));
    const std::vector<std::string> names{"weight", "bias"};
    for (size_t k = 0; k < names.size(); ++k) EXPECT_EQ(fast->named_parameters()[names[k]].sizes(),
                                                        reference->named_parameters()[names[k]].sizes());

    const torch::Tensor x = torch::randn({3, in, size, size});
    const torch::Tensor xa = x.clone().requires_grad_(), xb = x.clone().requires_grad_();
    const torch::Tensor ya = fast->forward(xa), yb = reference->forward(xb);
    ASSERT_EQ(ya.sizes(), yb.sizes());
    EXPECT_LT(relative(ya, yb), 1e-5);
    const torch::Tensor g = torch::randn(yb.sizes());
    (ya * g).sum().backward();
    (yb * g).sum().backward();
    EXPECT_LT(relative(xa.grad(), xb.grad()), 1e-5);
    EXPECT_LT(relative(fast->weight.grad(), reference->weight.grad()), 1e-5);
    EXPECT_LT(relative(fast->bias.grad(), reference->bias.grad()), 1e-5);
  }
}

TEST(Layers, ChannelsLastConvolutionIsLibTorchs) {
  torch::manual_seed(2);
  pl::ChannelsLastConv2d fast(16, 3, 3);
  torch::manual_seed(2);
  torch::nn::Conv2d reference(torch::nn::Conv2dOptions(16, 3, 3).padding(1));
  EXPECT_TRUE(torch::equal(fast->weight, reference->weight));
  const torch::Tensor x = torch::randn({2, 16, 12, 9});
  const torch::Tensor xa = x.clone().requires_grad_(), xb = x.clone().requires_grad_();
  const torch::Tensor ya = fast->forward(xa), yb = reference->forward(xb);
  EXPECT_TRUE(ya.is_contiguous());  // back in the default layout
  EXPECT_LT(relative(ya, yb), 1e-5);
  ya.sum().backward();
  yb.sum().backward();
  EXPECT_LT(relative(xa.grad(), xb.grad()), 1e-5);
  EXPECT_LT(relative(fast->weight.grad(), reference->weight.grad()), 1e-5);
}
