// The decoders' own last-layer kernel against a direct 3x3 convolution, in every build this CPU runs and every
// input layout the engine hands it: one block of all channels (the vectorised path), several blocks, planar.
#include "few_channel_conv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace pl = pixelcloth::learn;

namespace {

struct Case {
  int channels, block, out, height, width, batch;
};

/// out x in x 3 x 3 weights applied with padding 1 to the planar image, in double.
std::vector<float> direct(const std::vector<float>& planar, const std::vector<float>& weights,
                          const std::vector<float>& bias, const Case& c) {
  std::vector<float> result(static_cast<size_t>(c.batch) * c.out * c.height * c.width);
  for (int n = 0; n < c.batch; ++n)
    for (int o = 0; o < c.out; ++o)
      for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
          double sum = bias[o];
          for (int i = 0; i < c.channels; ++i)
            for (int ky = 0; ky < 3; ++ky)
              for (int kx = 0; kx < 3; ++kx) {
                const int yy = y + ky - 1, xx = x + kx - 1;
                if (yy < 0 || yy >= c.height || xx < 0 || xx >= c.width) continue;
                sum += static_cast<double>(weights[((o * c.channels + i) * 3 + ky) * 3 + kx]) *
                       planar[((n * c.channels + i) * c.height + yy) * c.width + xx];
              }
          result[((n * c.out + o) * c.height + y) * c.width + x] = static_cast<float>(sum);
        }
  return result;
}

}  // namespace

TEST(FewChannelConvolution, EqualsTheDirectSumInEveryBuildAndLayout) {
  const std::vector<std::string> builds = pl::fewChannelBuilds();
  ASSERT_EQ(builds.front(), "baseline");
  const std::vector<Case> cases{
      {16, 16, 3, 21, 37, 2},  // the patch decoder's 16 -> 3 in nChw16c, a width that is no multiple of 16
      {12, 12, 6, 19, 18, 1},  // the whole decoder's 12 -> 6 in nhwc: one run of 16 per row, and the buffer's end
      {2, 16, 3, 9, 40, 2},    // two channels padded to a block of 16
      {3, 3, 1, 6, 7, 3},      // a map too narrow for a run: every pixel one by one
      {1, 1, 3, 20, 20, 1},    // one channel, planar
      {24, 16, 3, 10, 20, 2},  // two blocks: the row kernel
      {5, 1, 2, 8, 12, 1},     // planar with several channels: the row kernel
  };
  std::mt19937 random(3);
  std::uniform_real_distribution<float> uniform(-1, 1);
  for (const Case& c : cases) {
    SCOPED_TRACE(std::to_string(c.channels) + " channels in blocks of " + std::to_string(c.block) + " -> " +
                 std::to_string(c.out) + ", " + std::to_string(c.height) + " x " + std::to_string(c.width));
    std::vector<float> planar(static_cast<size_t>(c.batch) * c.channels * c.height * c.width), weights(c.out * c.channels * 9),
        bias(c.out);
    for (float& v : planar) v = uniform(random);
    for (float& v : weights) v = uniform(random);
    for (float& v : bias) v = uniform(random);
    // batch x blocks x height x width x block, the padded channels zero (as oneDNN leaves them)
    const int blocks = (c.channels + c.block - 1) / c.block;
    std::vector<float> blocked(static_cast<size_t>(c.batch) * blocks * c.height * c.width * c.block, 0.0f);
    for (int n = 0; n < c.batch; ++n)
      for (int i = 0; i < c.channels; ++i)
        for (int p = 0; p < c.height * c.width; ++p)
          blocked[((n * blocks + i / c.block) * c.height * c.width + p) * c.block + i % c.block] =
              planar[(n * c.channels + i) * c.height * c.width + p];
    const std::vector<float> expected = direct(planar, weights, bias, c);
    const std::vector<float> packed = pl::fewChannelWeights(weights, c.out, c.channels, c.block);
    for (const std::string& build : builds) {
      std::vector<float> result(expected.size(), NAN);
      pl::fewChannelConvolution(blocked.data(), c.batch, c.height, c.width, c.channels, c.block, packed, bias, c.out,
                                result.data(), build);
      double worst = 0;
      for (size_t k = 0; k < result.size(); ++k) {
        const double difference = std::abs(double(result[k]) - expected[k]);
        worst = std::max(worst, std::isfinite(difference) ? difference : INFINITY);  // a pixel left unwritten is NaN
      }
      EXPECT_LT(worst, 1e-4) << build;
    }
  }
}
