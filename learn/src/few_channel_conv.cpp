#include "few_channel_conv.h"

#include <algorithm>

namespace pixelcloth::learn {

namespace {

/// One output row of every output channel: for each pixel, the dot products of the (up to) 3 x 3 window, one
/// contiguous run of 3 x block floats per channel block and kernel row, with each channel's weights.
__attribute__((always_inline)) inline void convolveRows(const float* src, std::int64_t batch, int height, int width,
                                                        int blocks, int block, const float* weights, const float* bias, int out,
                                                        float* dst) {
  const std::int64_t rows = batch * height;
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < rows; ++r) {
    const std::int64_t n = r / height;
    const int y = static_cast<int>(r % height);
    for (int o = 0; o < out; ++o) {
      float* row = dst + ((n * out + o) * height + y) * width;
      for (int x = 0; x < width; ++x) {
        const int x0 = std::max(x - 1, 0), x1 = std::min(x + 1, width - 1);
        const int length = (x1 - x0 + 1) * block, skip = (x0 - (x - 1)) * block;
        float sum = bias[o];
        for (int b = 0; b < blocks; ++b)
          for (int ky = 0; ky < 3; ++ky) {
            const int yy = y + ky - 1;
            if (yy < 0 || yy >= height) continue;
            const float* a = src + (((n * blocks + b) * height + yy) * width + x0) * block;
            const float* w = weights + ((o * blocks + b) * 3 + ky) * 3 * block + skip;
            float s = 0;
#pragma omp simd reduction(+ : s)
            for (int k = 0; k < length; ++k) s += a[k] * w[k];
            sum += s;
          }
        row[x] = sum;
      }
    }
  }
}

__attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,avx2,fma"))) void convolveAvx512(
    const float* src, std::int64_t batch, int height, int width, int blocks, int block, const float* weights,
    const float* bias, int out, float* dst) {
  convolveRows(src, batch, height, width, blocks, block, weights, bias, out, dst);
}

__attribute__((target("avx2,fma"))) void convolveAvx2(const float* src, std::int64_t batch, int height, int width,
                                                      int blocks, int block, const float* weights, const float* bias,
                                                      int out, float* dst) {
  convolveRows(src, batch, height, width, blocks, block, weights, bias, out, dst);
}

void convolveBaseline(const float* src, std::int64_t batch, int height, int width, int blocks, int block,
                      const float* weights, const float* bias, int out, float* dst) {
  convolveRows(src, batch, height, width, blocks, block, weights, bias, out, dst);
}

}  // namespace

std::vector<float> fewChannelWeights(const std::vector<float>& weights, int outChannels, int inChannels, int block) {
  const int blocks = (inChannels + block - 1) / block;
  std::vector<float> packed(static_cast<size_t>(outChannels) * blocks * 9 * block, 0.0f);
  for (int o = 0; o < outChannels; ++o)
    for (int i = 0; i < inChannels; ++i)
      for (int ky = 0; ky < 3; ++ky)
        for (int kx = 0; kx < 3; ++kx)
          packed[(((o * blocks + i / block) * 3 + ky) * 3 + kx) * block + i % block] =
              weights[((o * inChannels + i) * 3 + ky) * 3 + kx];
  return packed;
}

void fewChannelConvolution(const float* src, std::int64_t batch, int height, int width, int inChannels, int block,
                           const std::vector<float>& weights, const std::vector<float>& bias, int outChannels,
                           float* dst) {
  static const auto kernel = [] {
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl") &&
        __builtin_cpu_supports("avx512dq"))
      return &convolveAvx512;
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return &convolveAvx2;
    return &convolveBaseline;
  }();
  kernel(src, batch, height, width, (inChannels + block - 1) / block, block, weights.data(), bias.data(), outChannels, dst);
}

}  // namespace pixelcloth::learn
