#include "pixelcloth/learn/speed.h"

#include <torch/torch.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "model_impl.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/learn/cpu.h"

namespace pixelcloth::learn {

namespace {

using Clock = std::chrono::steady_clock;

using core::secondsSince;

}  // namespace

double sgemmGflops(int n, int threads, int repeats) {
  PIXELCLOTH_CHECK(n >= 1 && repeats >= 1, "sgemm: size " << n << ", " << repeats << " repeats");
  const ThreadScope scope(threads);
  torch::NoGradGuard noGrad;
  const torch::Tensor a = torch::rand({n, n}), b = torch::rand({n, n});
  torch::Tensor c = torch::mm(a, b);  // warm-up: the BLAS's threads and buffers
  double best = 1e30;
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    torch::mm_out(c, a, b);
    best = std::min(best, secondsSince(start));
  }
  return 2.0 * n * n * static_cast<double>(n) / best * 1e-9;
}

double trainStepSeconds(const ModelSpec& spec, int batch, int steps, int threads) {
  PIXELCLOTH_CHECK(batch >= 1 && steps >= 1, "train step: batch " << batch << ", " << steps << " steps");
  const ThreadScope scope(threads);
  keepFreedMemory();  // as train() does
  Model model(spec, 1);
  torch::nn::Sequential& net = ModelAccess::network(model);
  net->train();
  torch::optim::Adam adam(net->parameters(), torch::optim::AdamOptions(1e-3));
  const torch::Tensor inputs = torch::randn({batch, spec.inputs()});
  std::vector<std::int64_t> outputShape{batch};
  for (std::int64_t d : spec.outputShape()) outputShape.push_back(d);
  const torch::Tensor targets = torch::randn(outputShape);
  std::vector<double> times;
  for (int s = 0; s <= steps; ++s) {
    const auto start = Clock::now();
    adam.zero_grad();
    const torch::Tensor loss = (net->forward(inputs) - targets).abs().mean();
    loss.backward();
    adam.step();
    if (s > 0) times.push_back(secondsSince(start));
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

}  // namespace pixelcloth::learn
