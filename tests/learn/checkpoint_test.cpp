// The training checkpoint and weights files (learn/src/checkpoint.h): a restored run continues exactly, damaged or
// foreign contents are refused naming the file, and the LibTorch archives that crashed LibTorch's reader under
// fuzzing never reach it.

#include "checkpoint.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "model_impl.h"
#include "pixelcloth/core/tensor_file.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
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

// `steps` Adam steps on a fixed quadratic, so that the moments are not zero.
void step(torch::nn::Sequential& net, torch::optim::Adam& adam, int steps) {
  for (int k = 0; k < steps; ++k) {
    adam.zero_grad();
    torch::Tensor loss = net->forward(torch::ones({3, 4})).square().sum();
    loss.backward();
    adam.step();
  }
}

pl::NetworkReport twoEpochs() {
  pl::NetworkReport report;
  report.epochs.push_back({1, 0.5, 0.1, 0.2, 3.0, std::nan(""), 0.01, 0.001});
  report.epochs.push_back({2, 0.25, 0.1, 0.2, 2.0, 3.0, 0.01, 0.001});
  report.bestEpoch = 2;
  report.bestErrorCm = 3.0;
  return report;
}

// The file as saveCheckpoint wrote it, with `edit` applied to its arrays, written back.
void rewrite(const fs::path& from, const fs::path& to, const std::function<void(pc::TensorFile&)>& edit) {
  pc::TensorFile file = pc::readTensorFile(from, "checkpoint");
  edit(file);
  pc::writeTensorFile(to, file);
}

}  // namespace

// A resumed run must take the same steps as one that was never stopped: the weights and Adam's moments and step
// counts all come back.
TEST(Checkpoint, ARestoredRunStepsExactlyAsTheUninterruptedOne) {
  const fs::path dir = pt::freshDir("resume");
  torch::manual_seed(3);
  pl::Model first(tinySpec(), 1);
  torch::nn::Sequential& a = pl::ModelAccess::network(first);
  torch::optim::Adam adamA(a->parameters(), torch::optim::AdamOptions(0.01));
  step(a, adamA, 3);
  pl::saveCheckpoint(dir / "checkpoint.tensors", kSignature, a, adamA, twoEpochs());

  torch::manual_seed(4);  // other initial weights: the load must replace them
  pl::Model second(tinySpec(), 1);
  torch::nn::Sequential& b = pl::ModelAccess::network(second);
  torch::optim::Adam adamB(b->parameters(), torch::optim::AdamOptions(0.01));
  pl::NetworkReport report;
  pl::loadCheckpoint(dir / "checkpoint.tensors", kSignature, b, adamB, report);
  ASSERT_EQ(report.epochs.size(), 2u);
  EXPECT_TRUE(std::isnan(report.epochs[0].regularisationErrorCm));
  EXPECT_EQ(report.epochs[1].trainErrorCm, 2.0);
  EXPECT_EQ(report.bestEpoch, 2);
  EXPECT_EQ(report.bestErrorCm, 3.0);

  step(a, adamA, 2);
  step(b, adamB, 2);
  const auto pa = a->parameters(), pb = b->parameters();
  ASSERT_EQ(pa.size(), pb.size());
  for (size_t i = 0; i < pa.size(); ++i) EXPECT_TRUE(torch::equal(pa[i], pb[i])) << "parameter " << i;
}

TEST(Checkpoint, DamagedOrForeignContentsAreRefusedNamingTheFile) {
  const fs::path dir = pt::freshDir("records");
  pl::Model model(tinySpec(), 1);
  torch::nn::Sequential& net = pl::ModelAccess::network(model);
  torch::optim::Adam adam(net->parameters());
  step(net, adam, 1);
  const fs::path good = dir / "good.tensors";
  pl::saveCheckpoint(good, kSignature, net, adam, twoEpochs());
  auto find = [](pc::TensorFile& file, const std::string& name) -> pc::NpyArray& {
    for (auto& [key, array] : file.arrays)
      if (key == name) return array;
    throw std::runtime_error("no array " + name);
  };
  struct Case {
    const char* name;
    std::function<void(pc::TensorFile&)> edit;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"float32_records",
       [&](pc::TensorFile& f) { find(f, "records") = pc::NpyArray::from(std::vector<float>(16), {2, 8}); },
       "its epoch records are missing or not 8 float64 columns"},
      {"best_1x3", [&](pc::TensorFile& f) { find(f, "best") = pc::NpyArray::from(std::vector<double>(3), {1, 3}); },
       "its epoch records are missing or not 8 float64 columns"},
      {"no_moments", [&](pc::TensorFile& f) { f.arrays.erase(f.arrays.end() - 3); },
       "has no array 'adam/"},
      {"nan_weight",
       [&](pc::TensorFile& f) { reinterpret_cast<float*>(find(f, "model/0.weight").bytes.data())[2] = std::nanf(""); },
       "array 'model/0.weight' holds a value that is not finite (element 3, counting from 1)"},
      {"wider", [&](pc::TensorFile& f) { find(f, "model/0.bias").shape = {1, find(f, "model/0.bias").shape[0]}; },
       "array 'model/0.bias' is <f4 "},
      // Found by fuzzing: an epoch of 4e180 was converted to int (UBSan).
      {"epoch_overflow",
       [&](pc::TensorFile& f) { reinterpret_cast<double*>(find(f, "records").bytes.data())[0] = 4.2482e180; },
       "epoch record 1 is for epoch 4.2482e+180, expected 1 (the records are damaged)"},
      {"best_epoch_not_recorded",
       [&](pc::TensorFile& f) { reinterpret_cast<double*>(find(f, "best").bytes.data())[0] = 3; },
       "best epoch 3, expected one of the 2 recorded (or 0)"},
      {"steps_missing", [&](pc::TensorFile& f) { f.meta.erase("adam_steps"); }, "meta: missing field 'adam_steps'"},
      {"other_run", [&](pc::TensorFile& f) { f.meta["signature"]["format"] = "other"; },
       "holds a run with other settings (format: \"other\" there, \"test\" now)"},
  };
  for (const Case& c : cases) {
    const fs::path path = dir / (std::string(c.name) + ".tensors");
    rewrite(good, path, c.edit);
    pl::NetworkReport report;
    const std::string message = pt::inputErrorOf([&] { pl::loadCheckpoint(path, kSignature, net, adam, report); });
    EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << c.name << ": " << message;
    EXPECT_NE(message.find(c.message), std::string::npos) << c.name << ": " << message;
  }
  pl::NetworkReport report;
  pl::loadCheckpoint(good, kSignature, net, adam, report);  // the untouched one still loads
  EXPECT_EQ(report.epochs.size(), 2u);
}

// Found by fuzzing (docs/reliability.md, findings 11 to 13): LibTorch 1.13's archive reader threw
// torch::jit::ErrorReport, leaked its zip reader, read a wild pointer and freed what it had not allocated on these
// four mutated model.pt / checkpoint.pt files. Weights and checkpoints are tensor files now: the zips are refused
// before LibTorch sees them.
TEST(Checkpoint, LibTorchArchivesThatCrashedItAreRefusedNamingTheFile) {
  pl::Model model(tinySpec(), 1);
  torch::nn::Sequential& net = pl::ModelAccess::network(model);
  torch::optim::Adam adam(net->parameters());
  for (const char* name : {"fuzz_weights_unknown_type.pt", "fuzz_weights_libtorch_segv.pt"}) {
    const fs::path weights = pt::asset(name);
    const std::string message = pt::inputErrorOf([&] { pl::loadWeights(net, weights, "the test network"); });
    EXPECT_EQ(message.rfind(weights.string() + ": a zip file, as LibTorch archives are; ", 0), 0u) << message;
  }
  for (const char* name : {"fuzz_checkpoint_zip_leak.pt", "fuzz_checkpoint_libtorch_bad_free.pt"}) {
    const fs::path checkpoint = pt::asset(name);
    pl::NetworkReport report;
    const std::string message =
        pt::inputErrorOf([&] { pl::loadCheckpoint(checkpoint, kSignature, net, adam, report); });
    EXPECT_EQ(message.rfind(checkpoint.string() + ": a zip file, as LibTorch archives are; ", 0), 0u) << message;
    EXPECT_NE(message.find("delete it to start the run afresh"), std::string::npos) << message;
  }
}

TEST(Checkpoint, ASidecarWhoseFormatIsNotAStringIsRefused) {
  EXPECT_EQ(pt::inputErrorOf([] { pl::specOfSidecar(nlohmann::json{{"format", 5}}, "m/model.json"); }),
            "m/model.json: not a pixelcloth model (format '5')");
  EXPECT_EQ(pt::inputErrorOf([] { pl::specOfSidecar(nlohmann::json::array(), "m/model.json"); }),
            "m/model.json: not a pixelcloth model (format '')");
}

TEST(Checkpoint, ASidecarOfImpossibleSizesNamesItsFile) {
  const nlohmann::json good = {
      {"format", "pixelcloth.model"}, {"architecture", "whole"}, {"width", 0.125}, {"inputs", 0}, {"values", 0},
      {"pca_components", 0}};
  EXPECT_NO_THROW(pl::specOfSidecar(good, "m/model.json"));
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, nlohmann::json>>{{"width", 0}, {"inputs", -1}, {"inputs", 2000000000}}) {
    nlohmann::json bad = good;
    bad[key] = value;
    const std::string message = pt::inputErrorOf([&] { pl::specOfSidecar(bad, "m/model.json"); });
    EXPECT_EQ(message.rfind("m/model.json: model: ", 0), 0u) << message;
    EXPECT_NE(message.find("expected"), std::string::npos) << message;
  }
}
