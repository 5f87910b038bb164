#pragma once

// The decoders' last layer (learn/-internal): a 3x3 convolution to a few channels (16 -> 3 for a patch, 12 -> 6 for
// the whole garment at width 1). oneDNN's kernels are written for 16 or more output channels and fall to a gemm or
// padded path here. When every input channel sits in one block of at most 16 (nhwc, or nChw16c of up to 16
// channels: the decoders at width 1 and below), each pixel's window is nine 16-lane vectors, and the lanes of 16
// neighbouring pixels are added at once; otherwise it slides the 3 x C window of a channels-last row along it.

#include <cstdint>
#include <string>
#include <vector>

namespace pixelcloth::learn {

/// The input read in channel blocks of `block` channels, batch x ceil(in / block) x height x width x block (the
/// channels of the last block padded): oneDNN's nChw16c or nChw8c, nhwc (one block of all channels) or nchw (blocks
/// of 1).
/// LibTorch's out x in x 3 x 3 weights rearranged as the kernel reads them: out x blocks x 3 (rows) x 3 x block,
/// zero for the padded channels.
std::vector<float> fewChannelWeights(const std::vector<float>& weights, int outChannels, int inChannels, int block);

/// The kernel's builds this CPU runs, slowest first: "baseline", then "avx2", "avx512" where supported.
std::vector<std::string> fewChannelBuilds();

/// dst (batch x out x height x width, nchw) = bias + the 3x3 convolution, padding 1, of src (in channel blocks, as
/// above). Spreads rows over OpenMP's threads; runs `build` (one of fewChannelBuilds()), by default the fastest.
void fewChannelConvolution(const float* src, std::int64_t batch, int height, int width, int inChannels, int block,
                           const std::vector<float>& weights, const std::vector<float>& bias, int outChannels,
                           float* dst, const std::string& build = "");

}  // namespace pixelcloth::learn
