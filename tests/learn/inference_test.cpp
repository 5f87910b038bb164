// The oneDNN inference engine against LibTorch's eval-mode forward: every architecture at several widths, with
// BatchNorm statistics that are not the identity (so folding them is checked), batches of 1 and more, several
// networks spread over threads, and bad input.
#include "pixelcloth/learn/inference.h"

#include <gtest/gtest.h>
#include <torch/torch.h>

#include "model_impl.h"
#include "support/test_util.h"

namespace pl = pixelcloth::learn;
using pixelcloth::testing::inputErrorOf;

namespace {

pl::ModelSpec specOf(pl::Architecture architecture, double width, int inputs = 0) {
  pl::ModelSpec spec;
  spec.architecture = architecture;
  spec.width = width;
  spec.inputSize = inputs;
  spec.outputValues = 3 * 200;
  spec.pcaComponents = 16;
  return spec;
}

/// A model whose every parameter and BatchNorm statistic is random, as after some training.
pl::Model trainedLike(const pl::ModelSpec& spec, std::uint64_t seed) {
  pl::Model model(spec, seed);
  torch::NoGradGuard noGrad;
  torch::manual_seed(seed + 100);
  for (const auto& child : pl::ModelAccess::network(model)->children()) {
    if (auto* bn = child->as<torch::nn::BatchNorm2dImpl>()) {
      bn->running_mean.normal_(0, 0.2);
      bn->running_var.uniform_(0.3, 2.0);
      bn->weight.uniform_(0.5, 1.5);
      bn->bias.normal_(0, 0.1);
    }
    if (auto* pca = child->as<pl::PcaDecodeImpl>()) {
      pca->mean.normal_(0, 0.1);
      pca->basis.normal_(0, 0.1);
    }
  }
  return model;
}

pl::RowsF randomInputs(int batch, int inputs, unsigned seed) {
  std::srand(seed);
  return pl::RowsF::Random(batch, inputs);
}

/// max |a - b| over max |b|.
double relativeError(const pl::RowsF& a, const Eigen::MatrixXf& b) {
  EXPECT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.cols(), b.cols());
  if (a.rows() != b.rows() || a.cols() != b.cols()) return 1;
  return (a - b).cwiseAbs().maxCoeff() / std::max(1e-30f, b.cwiseAbs().maxCoeff());
}

}  // namespace

TEST(Inference, EqualsLibTorchForEveryArchitectureAndWidth) {
  for (pl::Architecture a : {pl::Architecture::Patch, pl::Architecture::Whole, pl::Architecture::Necktie,
                             pl::Architecture::FullyConnected, pl::Architecture::FullyConnectedPca}) {
    for (double width : {0.125, 0.25, 1.0}) {
      SCOPED_TRACE(std::string(pl::architectureName(a)) + " width " + std::to_string(width));
      const pl::ModelSpec spec = specOf(a, width);
      const pl::Model model = trainedLike(spec, 3);
      // One thread: every step in turn; three: a transposed convolution's four parts side by side, unevenly.
      for (int threads : {1, 3}) {
        const pl::CompiledNetworks compiled({&model}, threads);
        for (int batch : {1, 3}) {
          const pl::RowsF inputs = randomInputs(batch, spec.inputs(), 11 + batch);
          std::vector<pl::RowsF> outputs;
          compiled.forward(inputs, outputs);
          ASSERT_EQ(outputs.size(), 1u);
          const Eigen::MatrixXf reference = model.forward(inputs);
          EXPECT_GT(reference.cwiseAbs().maxCoeff(), 1e-3);  // not a trivially zero network
          EXPECT_LT(relativeError(outputs[0], reference), 1e-5) << "batch " << batch << ", " << threads << " threads";
        }
      }
    }
  }
}

TEST(Inference, SeveralNetworksOverThreadsEqualEachAlone) {
  // Residual patch decoders: pose plus marker features in.
  const pl::ModelSpec spec = specOf(pl::Architecture::Patch, 0.125, 90 + 3 * 20);
  std::vector<pl::Model> models;
  for (std::uint64_t seed = 0; seed < 5; ++seed) models.push_back(trainedLike(spec, seed));
  std::vector<const pl::Model*> pointers;
  for (const pl::Model& m : models) pointers.push_back(&m);
  const pl::CompiledNetworks compiled(pointers, 2);
  EXPECT_EQ(compiled.size(), 5);
  EXPECT_EQ(compiled.threads(), 2);
  for (int batch : {2, 1, 2}) {  // a second call at a batch size reuses its primitives
    const pl::RowsF inputs = randomInputs(batch, spec.inputs(), 5);
    std::vector<pl::RowsF> outputs;
    compiled.forward(inputs, outputs);
    ASSERT_EQ(outputs.size(), models.size());
    for (size_t n = 0; n < models.size(); ++n)
      EXPECT_LT(relativeError(outputs[n], models[n].forward(inputs)), 1e-5) << "network " << n << " batch " << batch;
  }
}

TEST(Inference, RefusesBadInput) {
  const pl::ModelSpec spec = specOf(pl::Architecture::FullyConnected, 0.125);
  const pl::Model model = trainedLike(spec, 1), other = trainedLike(specOf(pl::Architecture::Patch, 0.125), 1);
  EXPECT_NE(inputErrorOf([&] { pl::CompiledNetworks({&model, &other}); }).find("different specs"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { pl::CompiledNetworks({}); }).find("no networks"), std::string::npos);
  const pl::CompiledNetworks compiled({&model});
  std::vector<pl::RowsF> outputs;
  EXPECT_NE(inputErrorOf([&] { compiled.forward(pl::RowsF::Zero(1, 89), outputs); }).find("expected batch x 90"),
            std::string::npos);
  pl::RowsF nan = pl::RowsF::Zero(1, 90);
  nan(0, 4) = std::nanf("");
  EXPECT_NE(inputErrorOf([&] { compiled.forward(nan, outputs); }).find("not all finite"), std::string::npos);
  EXPECT_EQ(pl::engineFromName("onednn", "test"), pl::Engine::OneDnn);
  EXPECT_NE(inputErrorOf([&] { pl::engineFromName("mkl", "--engine"); }).find("libtorch"), std::string::npos);
}
