// The losses: zero on ground truth, and their LibTorch gradients against central finite differences on a tiny mesh.
#include "losses.h"

#include <gtest/gtest.h>

#include <functional>

namespace pl = pixelcloth::learn;

namespace {

/// A tiny open mesh: a 3 x 3 grid of vertices bent out of its plane, 8 triangles, counter-clockwise.
struct TinyMesh {
  torch::Tensor positions, faces, edges;
  TinyMesh() {
    std::vector<double> p;
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) p.insert(p.end(), {0.1 * x, 0.1 * y, 0.02 * (x - 1) * (x - 1) + 0.01 * y});
    positions = torch::tensor(p, torch::kFloat64).reshape({1, 9, 3});
    std::vector<std::int64_t> f, e;
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) {
        const std::int64_t a = 3 * y + x, b = a + 1, c = a + 3, d = a + 4;
        f.insert(f.end(), {a, b, d, a, d, c});
        e.insert(e.end(), {a, b, a, c, a, d});
      }
    faces = torch::tensor(f).reshape({8, 3});
    edges = torch::tensor(e).reshape({-1, 2});
  }
};

/// Checks d loss / d x against central differences, entry by entry (double precision).
void expectGradientMatches(const std::function<torch::Tensor(const torch::Tensor&)>& loss, torch::Tensor x,
                           double tolerance = 1e-6) {
  x = x.clone().set_requires_grad(true);
  loss(x).backward();
  const torch::Tensor analytic = x.grad().clone();
  torch::NoGradGuard noGrad;
  const double h = 1e-6;
  torch::Tensor flat = x.detach().clone().reshape({-1});
  const torch::Tensor grad = analytic.reshape({-1});
  for (std::int64_t i = 0; i < flat.numel(); ++i) {
    const double saved = flat[i].item<double>();
    flat[i] = saved + h;
    const double up = loss(flat.reshape(x.sizes())).item<double>();
    flat[i] = saved - h;
    const double down = loss(flat.reshape(x.sizes())).item<double>();
    flat[i] = saved;
    EXPECT_NEAR(grad[i].item<double>(), (up - down) / (2 * h), tolerance) << "entry " << i;
  }
}

}  // namespace

TEST(Losses, ZeroOnGroundTruth) {
  const TinyMesh mesh;
  const torch::Tensor image = torch::randn({2, 3, 4, 5}, torch::kFloat64), mask = (torch::rand({2, 1, 4, 5}) > 0.3);
  EXPECT_EQ(pl::maskedImageLoss(image, image, mask).item<double>(), 0.0);
  EXPECT_EQ(pl::maskedImageLoss(image, image, mask, pl::ImageLoss::L2).item<double>(), 0.0);
  EXPECT_NEAR(pl::normalLoss(mesh.positions, mesh.positions, mesh.faces).item<double>(), 0.0, 1e-12);
  EXPECT_EQ(pl::edgeLengthLoss(mesh.positions, mesh.positions, mesh.edges).item<double>(), 0.0);
  // A translation keeps normals and edge lengths.
  const torch::Tensor moved = mesh.positions + torch::tensor({0.3, -0.1, 0.2}, torch::kFloat64);
  EXPECT_NEAR(pl::normalLoss(moved, mesh.positions, mesh.faces).item<double>(), 0.0, 1e-12);
  EXPECT_NEAR(pl::edgeLengthLoss(moved, mesh.positions, mesh.edges).item<double>(), 0.0, 1e-12);
}

TEST(Losses, ImageLossCountsOnlyMaskedPixels) {
  const torch::Tensor target = torch::zeros({1, 2, 2, 2}, torch::kFloat64);
  torch::Tensor predicted = target.clone();
  predicted[0][0][0][0] = 3.0;  // masked: counts
  predicted[0][1][1][1] = 5.0;  // unmasked: ignored
  torch::Tensor mask = torch::zeros({1, 1, 2, 2});
  mask[0][0][0][0] = 1;
  mask[0][0][0][1] = 1;
  // Masked: 2 pixels x 2 channels = 4 values, one of them 3 off.
  EXPECT_DOUBLE_EQ(pl::maskedImageLoss(predicted, target, mask).item<double>(), 3.0 / 4);
  EXPECT_DOUBLE_EQ(pl::maskedImageLoss(predicted, target, mask, pl::ImageLoss::L2).item<double>(), 9.0 / 4);
}

TEST(Losses, GradientsMatchFiniteDifferences) {
  const TinyMesh mesh;
  torch::manual_seed(3);
  const torch::Tensor truth = mesh.positions;
  const torch::Tensor start = truth + 0.01 * torch::randn_like(truth);
  expectGradientMatches([&](const torch::Tensor& x) { return pl::normalLoss(x, truth, mesh.faces); }, start);
  expectGradientMatches([&](const torch::Tensor& x) { return pl::edgeLengthLoss(x, truth, mesh.edges); }, start);
  const torch::Tensor target = torch::randn({1, 3, 3, 4}, torch::kFloat64), mask = torch::rand({1, 1, 3, 4}) > 0.4;
  expectGradientMatches([&](const torch::Tensor& x) { return pl::maskedImageLoss(x, target, mask, pl::ImageLoss::L2); },
                        target + 0.1 * torch::randn_like(target));
  // The path of the normal loss from an image: sample operator, frames, positions, normals.
  const torch::Tensor sample = torch::rand({9, 12}, torch::kFloat64).to_sparse();
  const torch::Tensor origin = truth[0], t = torch::randn({9, 3}, torch::kFloat64),
                      b = torch::randn({9, 3}, torch::kFloat64), n = torch::randn({9, 3}, torch::kFloat64);
  expectGradientMatches(
      [&](const torch::Tensor& image) {
        const torch::Tensor offsets = pl::sampleImage(sample, image);
        return pl::normalLoss(pl::positionsFromOffsets(offsets, origin, t, b, n), truth, mesh.faces);
      },
      0.01 * torch::randn({1, 3, 3, 4}, torch::kFloat64), 1e-5);
}

TEST(Losses, SampleImageIsTheOperatorPerChannel) {
  const torch::Tensor image = torch::randn({2, 3, 2, 3}, torch::kFloat64);
  const torch::Tensor dense = torch::rand({4, 6}, torch::kFloat64);
  const torch::Tensor values = pl::sampleImage(dense.to_sparse(), image);
  ASSERT_EQ(values.sizes(), (std::vector<std::int64_t>{2, 4, 3}));
  for (int s = 0; s < 2; ++s)
    for (int c = 0; c < 3; ++c)
      EXPECT_TRUE(torch::allclose(values[s].select(1, c), dense.mv(image[s][c].reshape({-1}))));
}
