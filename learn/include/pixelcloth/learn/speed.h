#pragma once

// What `pixelcloth bench` measures of learn/ (DESIGN.md, "Inference"): the cores' sgemm peak, against which the
// decoders' speed is judged, and a training step of a decoder.

#include "pixelcloth/learn/model.h"

namespace pixelcloth::learn {

/// The BLAS LibTorch calls (OpenBLAS after scripts/setup) multiplying two n x n float matrices on `threads`
/// threads: GFLOP/s (2 n^3 per product), best of `repeats` after a warm-up.
double sgemmGflops(int n, int threads, int repeats = 3);

/// One Adam step of a freshly initialised network of `spec` in training mode (BatchNorm on batch statistics) at
/// `batch` random samples, L1 loss on its whole output, on `threads` threads: seconds, the median of `steps` after a
/// warm-up step. A step costs about 3 forward passes (summarize(spec).gflopForward x 3 x batch).
double trainStepSeconds(const ModelSpec& spec, int batch, int steps, int threads);

}  // namespace pixelcloth::learn
