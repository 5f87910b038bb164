#include "few_channel_conv.h"

#include <omp.h>

#include <algorithm>
#include <string>

namespace pixelcloth::learn {

namespace {

/// One output row of every output channel: for each pixel, the dot products of the (up to) 3 x 3 window, one
/// contiguous run of 3 x block floats per channel block and kernel row, with each channel's weights.
__attribute__((always_inline)) inline void convolveRows(const float* src, std::int64_t begin, std::int64_t end,
                                                        int height, int width, int blocks, int block,
                                                        const float* weights, const float* bias, int out, float* dst) {
  for (std::int64_t r = begin; r < end; ++r) {
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

/// Whether convolveOneBlock takes the layer: every input channel in one block of at most 16, at most 8 outputs.
bool oneBlock(int inChannels, int block, int outChannels) {
  return inChannels <= block && inChannels <= 16 && outChannels <= 8;
}

/// Sixteen floats, one AVX-512 register or two AVX2 ones as the function's target decides.
typedef float Vec16 __attribute__((vector_size(64), aligned(4)));
typedef std::int32_t Mask16 __attribute__((vector_size(64), aligned(4)));
// Two vectors' lanes picked by constant indices: GCC's __builtin_shuffle takes them as a mask vector, clang's
// __builtin_shufflevector as arguments (clang builds learn/ for the fuzz targets, scripts/run fuzz).
#if defined(__clang__)
#define PIXELCLOTH_SHUFFLE(a, b, ...) __builtin_shufflevector(a, b, __VA_ARGS__)
#else
#define PIXELCLOTH_SHUFFLE(a, b, ...) __builtin_shuffle(a, b, Mask16{__VA_ARGS__})
#endif

/// out[p] = bias + the sum of a[p]'s lanes, for p < 16. Each level adds the two halves
/// of neighbouring vectors' partial sums, keeping the pixels in order: 8, 4, 2, then 1 lane per pixel.
__attribute__((always_inline)) inline void laneSums(const Vec16* a, float bias, float* out) {
  Vec16 u[8], v[4], w[2];
  for (int i = 0; i < 8; ++i)
    u[i] = PIXELCLOTH_SHUFFLE(a[2 * i], a[2 * i + 1], 0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23) +
           PIXELCLOTH_SHUFFLE(a[2 * i], a[2 * i + 1], 8, 9, 10, 11, 12, 13, 14, 15, 24, 25, 26, 27, 28, 29, 30, 31);
  for (int j = 0; j < 4; ++j)
    v[j] = PIXELCLOTH_SHUFFLE(u[2 * j], u[2 * j + 1], 0, 1, 2, 3, 8, 9, 10, 11, 16, 17, 18, 19, 24, 25, 26, 27) +
           PIXELCLOTH_SHUFFLE(u[2 * j], u[2 * j + 1], 4, 5, 6, 7, 12, 13, 14, 15, 20, 21, 22, 23, 28, 29, 30, 31);
  for (int k = 0; k < 2; ++k)
    w[k] = PIXELCLOTH_SHUFFLE(v[2 * k], v[2 * k + 1], 0, 1, 4, 5, 8, 9, 12, 13, 16, 17, 20, 21, 24, 25, 28, 29) +
           PIXELCLOTH_SHUFFLE(v[2 * k], v[2 * k + 1], 2, 3, 6, 7, 10, 11, 14, 15, 18, 19, 22, 23, 26, 27, 30, 31);
  const Vec16 sums = PIXELCLOTH_SHUFFLE(w[0], w[1], 0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30) +
                     PIXELCLOTH_SHUFFLE(w[0], w[1], 1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31) +
                     bias;
  __builtin_memcpy(out, &sums, sizeof sums);
}

/// A pixel's 3 x 3 window of a channels-last image as nine vectors of 16 channels, the lanes past C zero. `full`: the
/// window lies inside and reading 16 floats at each tap stays in the buffer; else the taps outside are zero.
template <int C>
__attribute__((always_inline)) inline void windowAt(const float* image, int height, int width, int block, int y, int x,
                                                    bool full, Vec16* window) {
  if (full) {
    Mask16 keep;
    for (int c = 0; c < 16; ++c) keep[c] = c < C ? -1 : 0;
    for (int t = 0; t < 9; ++t) {
      Vec16 v;
      __builtin_memcpy(&v, image + ((y + t / 3 - 1) * width + (x + t % 3 - 1)) * block, sizeof v);
      if constexpr (C < 16) v = (Vec16)((Mask16)v & keep);
      window[t] = v;
    }
    return;
  }
  for (int t = 0; t < 9; ++t) {
    window[t] = Vec16{};
    const int yy = y + t / 3 - 1, xx = x + t % 3 - 1;
    if (yy >= 0 && yy < height && xx >= 0 && xx < width)
      __builtin_memcpy(&window[t], image + (yy * width + xx) * block, C * sizeof(float));
  }
}

/// *acc = the window's products with one output channel's 9 x 16 weights, summed over the taps.
__attribute__((always_inline)) inline void products(const Vec16* window, const float* weights, Vec16* acc) {
  Vec16 sum{};
  for (int t = 0; t < 9; ++t) {
    Vec16 k;
    __builtin_memcpy(&k, weights + 16 * t, sizeof k);
    sum += window[t] * k;
  }
  *acc = sum;
}

/// The common case, every channel in one block (nhwc, or one block of nChw16c): each pixel's window as nine vectors,
/// one vector of the nine products' sums per output channel, and the lanes of 16 neighbouring pixels' vectors added
/// at once (laneSums). `weights` are out x 9 x 16 here. The map's border pixels, and rows where a 16-float read would
/// pass the buffer's end, take their taps one by one. (Helpers are inlined, not lambdas: a lambda is a function of
/// its own, built without the caller's target attribute.)
template <int C>
__attribute__((always_inline)) inline void convolveOneBlock(const float* src, std::int64_t begin, std::int64_t end,
                                                            int height, int width, int block, const float* weights,
                                                            const float* bias, int out, float* dst) {
  static_assert(C >= 1 && C <= 16);
  constexpr int kMaxOut = 8;
  // A full 16-float load at the map's last pixel reads past the buffer unless the block holds 16 floats.
  const int lastFullRow = block >= 16 ? height - 2 : height - 3;
  const std::int64_t plane = static_cast<std::int64_t>(height) * width;
  for (std::int64_t r = begin; r < end; ++r) {
    const std::int64_t n = r / height;
    const int y = static_cast<int>(r % height);
    const float* image = src + n * plane * block;
    float* row = dst + n * out * plane + static_cast<std::int64_t>(y) * width;  // channel o's row at row + o * plane
    // Runs of 16 from x = 1, the last one moved back to end at width - 2 (it repeats a few pixels, same values).
    const bool runs = y > 0 && y <= lastFullRow && width >= 18;
    for (int x = 1; runs && x + 16 <= width - 1 + 15; x += 16) {
      const int start = std::min(x, width - 17);
      Vec16 acc[kMaxOut][16];
      for (int p = 0; p < 16; ++p) {
        Vec16 window[9];
        windowAt<C>(image, height, width, block, y, start + p, true, window);
        for (int o = 0; o < out; ++o) products(window, weights + o * 9 * 16, &acc[o][p]);
      }
      for (int o = 0; o < out; ++o) laneSums(acc[o], bias[o], row + o * plane + start);
    }
    for (int x = 0; x < width; x += runs ? width - 1 : 1) {
      Vec16 window[9], acc;
      windowAt<C>(image, height, width, block, y, x, false, window);
      for (int o = 0; o < out; ++o) {
        products(window, weights + o * 9 * 16, &acc);
        float sum = bias[o];
        for (int c = 0; c < 16; ++c) sum += acc[c];
        row[o * plane + x] = sum;
      }
    }
  }
}

/// Output rows [begin, end) of the batch (row r is image r / height, row r % height): convolveOneBlock's
/// instantiation for the channel count when oneBlock() takes the layer, else convolveRows.
__attribute__((always_inline)) inline void convolveRange(const float* src, std::int64_t begin, std::int64_t end,
                                                         int height, int width, int channels, int block,
                                                         const float* weights, const float* bias, int out, float* dst) {
  if (oneBlock(channels, block, out)) {
    switch (channels) {
#define PIXELCLOTH_FEW_CHANNEL_CASE(C)                                                      \
  case C:                                                                                   \
    return convolveOneBlock<C>(src, begin, end, height, width, block, weights, bias, out, dst);
      PIXELCLOTH_FEW_CHANNEL_CASE(1) PIXELCLOTH_FEW_CHANNEL_CASE(2) PIXELCLOTH_FEW_CHANNEL_CASE(3)
      PIXELCLOTH_FEW_CHANNEL_CASE(4) PIXELCLOTH_FEW_CHANNEL_CASE(5) PIXELCLOTH_FEW_CHANNEL_CASE(6)
      PIXELCLOTH_FEW_CHANNEL_CASE(7) PIXELCLOTH_FEW_CHANNEL_CASE(8) PIXELCLOTH_FEW_CHANNEL_CASE(9)
      PIXELCLOTH_FEW_CHANNEL_CASE(10) PIXELCLOTH_FEW_CHANNEL_CASE(11) PIXELCLOTH_FEW_CHANNEL_CASE(12)
      PIXELCLOTH_FEW_CHANNEL_CASE(13) PIXELCLOTH_FEW_CHANNEL_CASE(14) PIXELCLOTH_FEW_CHANNEL_CASE(15)
      PIXELCLOTH_FEW_CHANNEL_CASE(16)
#undef PIXELCLOTH_FEW_CHANNEL_CASE
    }
  }
  convolveRows(src, begin, end, height, width, (channels + block - 1) / block, block, weights, bias, out, dst);
}

// One build per instruction set. The row loop is split over threads outside them: GCC outlines an OpenMP region's
// body into a function of its own that does not inherit the target attribute, which left both kernels SSE2 code.
using RangeKernel = void (*)(const float*, std::int64_t, std::int64_t, int, int, int, int, const float*, const float*,
                             int, float*);

__attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,avx2,fma"))) void convolveAvx512(
    const float* src, std::int64_t begin, std::int64_t end, int height, int width, int channels, int block,
    const float* weights, const float* bias, int out, float* dst) {
  convolveRange(src, begin, end, height, width, channels, block, weights, bias, out, dst);
}

__attribute__((target("avx2,fma"))) void convolveAvx2(const float* src, std::int64_t begin, std::int64_t end,
                                                      int height, int width, int channels, int block,
                                                      const float* weights, const float* bias, int out, float* dst) {
  convolveRange(src, begin, end, height, width, channels, block, weights, bias, out, dst);
}

void convolveBaseline(const float* src, std::int64_t begin, std::int64_t end, int height, int width, int channels,
                      int block, const float* weights, const float* bias, int out, float* dst) {
  convolveRange(src, begin, end, height, width, channels, block, weights, bias, out, dst);
}

}  // namespace

std::vector<float> fewChannelWeights(const std::vector<float>& weights, int outChannels, int inChannels, int block) {
  if (oneBlock(inChannels, block, outChannels)) {  // out x 9 x 16
    std::vector<float> packed(static_cast<size_t>(outChannels) * 9 * 16, 0.0f);
    for (int o = 0; o < outChannels; ++o)
      for (int i = 0; i < inChannels; ++i)
        for (int t = 0; t < 9; ++t) packed[(o * 9 + t) * 16 + i] = weights[(o * inChannels + i) * 9 + t];
    return packed;
  }
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

std::vector<std::string> fewChannelBuilds() {
  __builtin_cpu_init();
  std::vector<std::string> builds{"baseline"};
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) builds.push_back("avx2");
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512dq"))
    builds.push_back("avx512");
  return builds;
}

void fewChannelConvolution(const float* src, std::int64_t batch, int height, int width, int inChannels, int block,
                           const std::vector<float>& weights, const std::vector<float>& bias, int outChannels,
                           float* dst, const std::string& build) {
  static const std::string best = fewChannelBuilds().back();
  const std::string& chosen = build.empty() ? best : build;
  const RangeKernel kernel = chosen == "avx512" ? &convolveAvx512 : chosen == "avx2" ? &convolveAvx2 : &convolveBaseline;
  const std::int64_t rows = batch * height;
#pragma omp parallel
  {
    const std::int64_t threads = omp_get_num_threads(), t = omp_get_thread_num();
    kernel(src, rows * t / threads, rows * (t + 1) / threads, height, width, inChannels, block, weights.data(),
           bias.data(), outChannels, dst);
  }
}

}  // namespace pixelcloth::learn
