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
