// The paper's decoders and the fully connected baselines: parameter counts as the appendix states them, shapes, the
// summary against the built module, the width multiplier, and PCA.
#include "pixelcloth/learn/model.h"

#include <gtest/gtest.h>

#include "support/test_util.h"

namespace pl = pixelcloth::learn;
using pixelcloth::testing::inputErrorOf;

namespace {
pl::ModelSpec specOf(pl::Architecture architecture, double width = 1.0, int values = 0) {
  pl::ModelSpec spec;
  spec.architecture = architecture;
  spec.width = width;
  spec.outputValues = values;
  return spec;
}
}  // namespace

TEST(Model, ParameterCountsAreThePapers) {
  // Appendix: whole garment 3.79M, patch 3.96M, necktie 2.16M (DESIGN.md "Networks" for the necktie's map).
  const pl::ModelSummary whole = pl::summarize(specOf(pl::Architecture::Whole));
  const pl::ModelSummary patch = pl::summarize(specOf(pl::Architecture::Patch));
  const pl::ModelSummary tie = pl::summarize(specOf(pl::Architecture::Necktie));
  EXPECT_NEAR(whole.parameters / 1e6, 3.79, 0.005) << whole.parameters;
  EXPECT_NEAR(patch.parameters / 1e6, 3.96, 0.005) << patch.parameters;
  EXPECT_NEAR(tie.parameters / 1e6, 2.16, 0.005) << tie.parameters;
  // Exactly: the layers' weights and biases plus BatchNorm's scale and shift.
  EXPECT_EQ(whole.parameters, 3786090);
  EXPECT_EQ(patch.parameters, 3961219);
  EXPECT_EQ(tie.parameters, 2161795);
  EXPECT_EQ(whole.output, (std::vector<std::int64_t>{6, 256, 256}));
  EXPECT_EQ(patch.output, (std::vector<std::int64_t>{3, 160, 160}));
  EXPECT_EQ(tie.output, (std::vector<std::int64_t>{3, 256, 64}));  // the cloth image of the hanging tie
  EXPECT_EQ(whole.input, (std::vector<std::int64_t>{90}));
  EXPECT_EQ(tie.input, (std::vector<std::int64_t>{36}));
}

TEST(Model, SummaryCountsWhatTheBuiltModuleHolds) {
  for (pl::Architecture a : {pl::Architecture::Whole, pl::Architecture::Patch, pl::Architecture::Necktie,
                             pl::Architecture::FullyConnected, pl::Architecture::FullyConnectedPca}) {
    for (double width : {1.0, 0.25}) {
      SCOPED_TRACE(std::string(pl::architectureName(a)) + " width " + std::to_string(width));
      const pl::ModelSpec spec = specOf(a, width, 3 * 500);
      EXPECT_EQ(pl::Model(spec).parameters(), pl::summarize(spec).parameters);
    }
  }
}

TEST(Model, WidthScalesTheChannelsAndTheCost) {
  const pl::ModelSummary full = pl::summarize(specOf(pl::Architecture::Patch));
  pl::ModelSpec plainQuarter = specOf(pl::Architecture::Patch, 0.25);
  plainQuarter.minChannels = 0;
  const pl::ModelSummary quarter = pl::summarize(plainQuarter);
  EXPECT_EQ(quarter.output, full.output);
  // Convolutions scale with the square of the width, the first linear layer with the width.
  EXPECT_LT(quarter.parameters, full.parameters / 3);
  EXPECT_LT(quarter.gflopForward, full.gflopForward / 10);
  // The channel floor keeps the last layers' 16 channels: more arithmetic where the image is large.
  const pl::ModelSummary floored = pl::summarize(specOf(pl::Architecture::Patch, 0.25));
  EXPECT_GT(floored.gflopForward, quarter.gflopForward);
  EXPECT_LT(floored.gflopForward, full.gflopForward / 4);
  EXPECT_GT(full.gflopForward, 0.1);
  EXPECT_EQ(quarter.layers.front().name, "linear 90->3200");  // 5 x 5 x 128
}

TEST(Model, ForwardGivesOneOutputPerSampleAndIsSeeded) {
  const pl::ModelSpec spec = specOf(pl::Architecture::Whole, 0.125);
  const pl::Model a(spec, 7), b(spec, 7), c(spec, 8);
  const Eigen::MatrixXf poses = Eigen::MatrixXf::Random(2, 90);
  const Eigen::MatrixXf out = a.forward(poses);
  ASSERT_EQ(out.rows(), 2);
  ASSERT_EQ(out.cols(), 6 * 256 * 256);
  EXPECT_TRUE(out.allFinite());
  EXPECT_EQ(out, b.forward(poses));
  EXPECT_NE(out, c.forward(poses));
  // One sample alone gives the same row as in the batch (BatchNorm in eval mode).
  EXPECT_LT((a.forward(poses.topRows(1)) - out.topRows(1)).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(Model, PcaWithEveryComponentReproducesItsData) {
  // 12 samples of 30 values on a 5-dimensional affine subspace.
  const Eigen::MatrixXf coefficients = Eigen::MatrixXf::Random(12, 5), directions = Eigen::MatrixXf::Random(5, 30);
  const Eigen::RowVectorXf offset = Eigen::RowVectorXf::Random(30);
  const Eigen::MatrixXf data = (coefficients * directions).rowwise() + offset;
  const pl::PcaBasis basis = pl::fitPca(data, 5);
  EXPECT_LT((basis.reconstruct(basis.project(data)) - data).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_LT((basis.components * basis.components.transpose() - Eigen::MatrixXf::Identity(5, 5)).cwiseAbs().maxCoeff(),
            1e-5);
  for (int k = 1; k < 5; ++k) EXPECT_GE(basis.variance[k - 1], basis.variance[k]);
  // Fewer components lose what the smallest ones carried.
  const pl::PcaBasis two = pl::fitPca(data, 2);
  EXPECT_GT((two.reconstruct(two.project(data)) - data).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(Model, FcPcaDecodesThroughItsBasis) {
  pl::ModelSpec spec = specOf(pl::Architecture::FullyConnectedPca, 0.25, 30);
  spec.pcaComponents = 5;
  pl::Model model(spec, 1);
  const Eigen::MatrixXf data = Eigen::MatrixXf::Random(12, 30);
  const pl::PcaBasis basis = pl::fitPca(data, 5);
  model.setPcaBasis(basis.mean, basis.components);
  const Eigen::MatrixXf out = model.forward(Eigen::MatrixXf::Random(3, 90));
  // Every output lies in the basis' span around its mean.
  EXPECT_LT((basis.reconstruct(basis.project(out)) - out).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_NE(inputErrorOf([&] { model.setPcaBasis(basis.mean, basis.components.topRows(4)); }).find("expected 5 x 30"),
            std::string::npos);
}

TEST(Model, DecodersKeepAFloorOfChannelsAtSmallWidths) {
  // Channels of the last upsampling layer (before the 3x3 convolution to the offsets).
  auto lastChannels = [](pl::Architecture a, double width, int floor) {
    pl::ModelSpec spec = specOf(a, width);
    spec.minChannels = floor;
    const pl::ModelSummary summary = pl::summarize(spec);
    return summary.layers[summary.layers.size() - 2].output.front();
  };
  // Scaled down with the rest, a width-0.125 decoder draws its 6 (3) channels from 2.
  EXPECT_EQ(lastChannels(pl::Architecture::Whole, 0.125, 0), 2);
  EXPECT_EQ(lastChannels(pl::Architecture::Patch, 0.125, 0), 2);
  // With the floor: 16, or the paper's own count where it is smaller (the whole decoder's last 12).
  EXPECT_EQ(lastChannels(pl::Architecture::Whole, 0.125, 16), 12);
  EXPECT_EQ(lastChannels(pl::Architecture::Patch, 0.125, 16), 16);
  EXPECT_EQ(lastChannels(pl::Architecture::Necktie, 0.25, 16), 8);
  // At the paper's width the floor changes nothing.
  pl::ModelSpec plain = specOf(pl::Architecture::Patch);
  plain.minChannels = 0;
  EXPECT_EQ(pl::summarize(plain).parameters, pl::summarize(specOf(pl::Architecture::Patch)).parameters);
  pl::ModelSpec bad = specOf(pl::Architecture::Whole);
  bad.minChannels = -1;
  EXPECT_NE(inputErrorOf([&] { pl::summarize(bad); }).find("minimum channels -1"), std::string::npos);
}

TEST(Model, BadSpecsAndInputsAreRefused) {
  EXPECT_NE(inputErrorOf([] { pl::summarize(specOf(pl::Architecture::Patch, 0)); }).find("width"), std::string::npos);
  EXPECT_NE(inputErrorOf([] { pl::summarize(specOf(pl::Architecture::FullyConnected)); }).find("output size"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([] { pl::architectureFromName("cnn", "--arch"); }).find("whole, patch, necktie, fc or fc-pca"),
            std::string::npos);
  const pl::Model model(specOf(pl::Architecture::Necktie, 0.25));
  EXPECT_NE(inputErrorOf([&] { model.forward(Eigen::MatrixXf::Zero(1, 90)); }).find("expected batch x 36"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([] { pl::fitPca(Eigen::MatrixXf::Random(4, 10), 5); }).find("expected 1 to 4"),
            std::string::npos);
}
