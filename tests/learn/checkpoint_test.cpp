// The training checkpoint reader (learn/src/checkpoint.h) on archives that LibTorch reads without complaint but whose
// epoch records have the wrong type or rank: found while writing the checkpoint fuzz target (docs/reliability.md).
// Before the fix, data_ptr<double> on float32 records and item() on a 1 x 2 "best" escaped as LibTorch's c10::Error
// (the CLI's "internal error", exit 1) instead of an InputError naming the file.

#include "checkpoint.h"

#include <gtest/gtest.h>

#include "model_impl.h"
#include "support/test_util.h"

namespace pl = pixelcloth::learn;
namespace pt = pixelcloth::testing;
namespace fs = std::filesystem;

namespace {

pl::ModelSpec tinySpec() {
  pl::ModelSpec spec;
  spec.architecture = pl::Architecture::FullyConnected;
  spec.width = 0.05;
  spec.inputSize = 4;
  spec.outputValues = 6;
  return spec;
}

const nlohmann::json kSignature = {{"format", "test"}};

// A checkpoint as saveCheckpoint writes it, but with `records` and `best` as given.
void writeCheckpoint(const fs::path& path, torch::nn::Sequential& net, torch::optim::Adam& adam,
                     const torch::Tensor& records, const torch::Tensor& best) {
  torch::serialize::OutputArchive archive, model, optimizer;
  net->save(model);
  adam.save(optimizer);
  archive.write("model", model);
  archive.write("optimizer", optimizer);
  archive.write("signature", c10::IValue(kSignature.dump()));
  archive.write("records", records);
  archive.write("best", best);
  archive.save_to(path.string());
}

}  // namespace

TEST(Checkpoint, RecordsOfAnotherTypeOrRankAreRefusedNamingTheFile) {
  const fs::path dir = pt::freshDir("records");
  pl::Model model(tinySpec(), 1);
  torch::nn::Sequential& net = pl::ModelAccess::network(model);
  torch::optim::Adam adam(net->parameters());
  const torch::Tensor goodRecords = torch::zeros({2, 8}, torch::kFloat64);
  const torch::Tensor goodBest = torch::tensor({2.0, 1.5}, torch::kFloat64);
  struct Case {
    const char* name;
    torch::Tensor records, best;
  };
  for (const Case& c : {Case{"float32_records", goodRecords.to(torch::kFloat32), goodBest},
                        Case{"float32_best", goodRecords, goodBest.to(torch::kFloat32)},
                        Case{"best_1x2", goodRecords, goodBest.reshape({1, 2})}}) {
    const fs::path path = dir / (std::string(c.name) + ".pt");
    writeCheckpoint(path, net, adam, c.records, c.best);
    pl::NetworkReport report;
    const std::string message = pt::inputErrorOf([&] { pl::loadCheckpoint(path, kSignature, net, adam, report); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << c.name << ": " << message;
  }
  // The well-formed one still loads.
  writeCheckpoint(dir / "good.pt", net, adam, goodRecords, goodBest);
  pl::NetworkReport report;
  pl::loadCheckpoint(dir / "good.pt", kSignature, net, adam, report);
  EXPECT_EQ(report.epochs.size(), 2u);
  EXPECT_EQ(report.bestEpoch, 2);
}

// Found by fuzzing (docs/reliability.md): LibTorch throws torch::jit::ErrorReport, not c10::Error, for a pickle that
// names a type it cannot parse, and model.json readers called json.value("format", "") on a "format" of another type
// (nlohmann's type_error). Both escaped as the CLI's "internal error" instead of naming the file.
TEST(Checkpoint, DamagedArchivesFromFuzzingAreRefusedNamingTheFile) {
  pl::Model model(tinySpec(), 1);
  torch::nn::Sequential& net = pl::ModelAccess::network(model);
  const fs::path weights = pt::asset("fuzz_weights_unknown_type.pt");
  std::string message = pt::inputErrorOf([&] { pl::loadWeights(net, weights, "the test network"); });
  EXPECT_EQ(message.rfind(weights.string() + ": not the weights of the test network (truncated, or from another "
                                             "model): ",
                          0),
            0u)
      << message;
  // A zip that is no LibTorch archive (LibTorch leaks its zip reader on it: tests/sanitize/lsan.supp).
  torch::optim::Adam adam(net->parameters());
  pl::NetworkReport report;
  const fs::path checkpoint = pt::asset("fuzz_checkpoint_zip_leak.pt");
  message = pt::inputErrorOf([&] { pl::loadCheckpoint(checkpoint, kSignature, net, adam, report); });
  EXPECT_EQ(message.rfind(checkpoint.string() + ": not a pixelcloth training checkpoint (truncated or damaged): ", 0), 0u)
      << message;
}

TEST(Checkpoint, ASidecarWhoseFormatIsNotAStringIsRefused) {
  EXPECT_EQ(pt::inputErrorOf([] { pl::specOfSidecar(nlohmann::json{{"format", 5}}, "m/model.json"); }),
            "m/model.json: not a pixelcloth model (format '5')");
  EXPECT_EQ(pt::inputErrorOf([] { pl::specOfSidecar(nlohmann::json::array(), "m/model.json"); }),
            "m/model.json: not a pixelcloth model (format '')");
}
