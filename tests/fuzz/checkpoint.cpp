// learn::loadCheckpoint: a training run's checkpoint.tensors (weights, optimizer state, signature, epoch
// records; a tensor file, core/tensor_file.h).
#include "fuzz_network.h"
#include "fuzz_support.h"

namespace {
const nlohmann::json kSignature = {{"format", "pixelcloth.fuzz"}, {"epochs", 2}};

struct Run {
  pixelcloth::learn::Model model{pixelcloth::fuzz::fuzzSpec(), 1};
  torch::optim::Adam adam{pixelcloth::learn::ModelAccess::network(model)->parameters()};
};
Run& run() {
  static Run r;
  return r;
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  torch::set_num_threads(1);
  if (const char* out = pixelcloth::fuzz::seedOut()) {
    // One step, so that the seed holds Adam's moments as a resumed run's checkpoint does.
    torch::Tensor sum = torch::zeros({});
    for (const torch::Tensor& p : pixelcloth::learn::ModelAccess::network(run().model)->parameters())
      sum = sum + p.square().sum();
    sum.backward();
    run().adam.step();
    pixelcloth::learn::NetworkReport report;
    report.epochs.push_back({1, 0.5, 0.1, 0.2, 3.0, 4.0, 0.01, 0.001});
    report.epochs.push_back({2, 0.25, 0.1, 0.2, 2.0, 3.0, 0.01, 0.001});
    report.bestEpoch = 2;
    report.bestErrorCm = 3.0;
    pixelcloth::learn::saveCheckpoint(std::filesystem::path(out) / "checkpoint.tensors", kSignature,
                                      pixelcloth::learn::ModelAccess::network(run().model), run().adam, report);
    pixelcloth::fuzz::writeDeepMetaSeed(std::filesystem::path(out) / "checkpoint.tensors", "checkpoint");
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("checkpoint.tensors", data, size);
  pixelcloth::learn::NetworkReport report;
  return pixelcloth::fuzz::guarded([&] {
    pixelcloth::learn::loadCheckpoint(path, kSignature, pixelcloth::learn::ModelAccess::network(run().model),
                                      run().adam, report);
  });
}
