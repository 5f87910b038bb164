// Training on small synthetic datasets: decoders and baselines learn, checkpoints reload and resume, patch decoders
// train in subsets, and wrong models and damaged checkpoints are refused.
#include "pixelcloth/learn/train.h"

#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/training_data.h"
#include "pixelcloth/patches/patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/garment/garment.h"
#include "support/body_fixtures.h"
#include "support/synthetic_dataset.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
namespace pb = pixelcloth::body;
namespace pc = pixelcloth::core;
namespace pd = pixelcloth::data;
namespace pg = pixelcloth::garment;
namespace pl = pixelcloth::learn;
using pixelcloth::testing::inputErrorOf;

namespace {

/// 10 necktie samples (8 train, 1 regularisation, 1 test with seed 5).
const fs::path& necktieDataset() {
  static const fs::path folder = pixelcloth::testing::syntheticDataset("learn", "necktie", 10);
  return folder;
}

/// 6 T-shirt samples.
const fs::path& shirtDataset() {
  static const fs::path folder = pixelcloth::testing::syntheticDataset("learn", "tshirt", 6);
  return folder;
}

/// Mean per-vertex error (cm) of a trained model on some rows: its (single) network's values against the targets.
double errorOf(const pl::TrainedModel& model, const pl::TrainingData& data, const std::vector<int>& rows) {
  Eigen::MatrixXf inputs(rows.size(), data.inputs.cols());
  for (size_t k = 0; k < rows.size(); ++k) inputs.row(k) = data.inputs.row(rows[k]);
  const std::vector<pl::NetworkPrediction> predicted = model.predict(inputs);
  double error = 0;
  for (size_t k = 0; k < rows.size(); ++k) {
    const pl::NetworkPrediction& p = predicted.front();
    for (size_t i = 0; i < p.vertices.size(); ++i)
      error += (p.values.block<1, 3>(k, 3 * i) - data.values[rows[k]].row(p.vertices[i])).norm() / p.vertices.size();
  }
  return 100 * error / rows.size();
}

pl::TrainOptions necktieOptions(int epochs) {
  pl::TrainOptions options;
  options.model.architecture = pl::Architecture::Necktie;
  options.model.width = 0.25;
  options.epochs = epochs;
  options.batch = 4;
  options.learningRate = 2e-3;
  options.seed = 1;
  return options;
}

}  // namespace

TEST(Train, ANecktieDecoderLearnsItsTrainingSamples) {
  const fs::path out = pixelcloth::testing::freshDir("model");
  const pl::TrainReport trained = pl::train(necktieDataset(), out, necktieOptions(150));
  ASSERT_EQ(trained.networks.size(), 1u);
  const pl::NetworkReport& report = trained.networks.front();
  ASSERT_EQ(report.epochs.size(), 150u);
  const double first = report.epochs.front().trainErrorCm, last = report.epochs.back().trainErrorCm;
  std::cout << "[necktie width 0.25, 8 samples] train error " << first << " cm after epoch 1, " << last
            << " cm after 150; regularisation " << report.epochs.back().regularisationErrorCm << " cm\n";
  // It starts at zero offsets (the last layer is zero-initialised), 2.5 cm off; after 150 epochs 0.7 cm.
  EXPECT_LT(last, 1.0);
  EXPECT_LT(last, first / 3);
  EXPECT_GT(report.epochs.back().normalLoss, 0);  // the necktie's normal and edge terms are on by default
  EXPECT_GT(report.epochs.back().edgeLoss, 0);
  for (const char* file : {"model.tensors", "model.json", "log.csv", "checkpoint.tensors"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  std::ifstream log(out / "log.csv");
  int lines = 0;
  for (std::string line; std::getline(log, line);) ++lines;
  EXPECT_EQ(lines, 151);
}

TEST(Train, ATinyBaselineOverfitsEightSamples) {
  // fc-pca at quarter width (64 hidden units) with the train split's 8 components: 20K parameters.
  pl::TrainOptions options = necktieOptions(500);
  options.model.architecture = pl::Architecture::FullyConnectedPca;
  options.model.pcaComponents = 8;
  options.normalWeight = options.edgeWeight = 0;
  options.space = pl::OffsetSpace::Local;
  options.batch = 8;
  options.learningRate = 3e-3;
  const fs::path out = pixelcloth::testing::freshDir("model");
  const pl::NetworkReport report = pl::train(necktieDataset(), out, options).networks.front();
  std::cout << "[fc-pca width 0.25, 8 necktie samples] train error " << report.epochs.front().trainErrorCm << " cm after epoch 1, "
            << report.epochs.back().trainErrorCm << " cm after " << report.epochs.size() << "\n";
  EXPECT_LT(report.epochs.back().trainErrorCm, 0.05);
}

TEST(Train, TheCheckpointReloadsToItsRecordedError) {
  const fs::path out = pixelcloth::testing::freshDir("model");
  const pl::NetworkReport report = pl::train(necktieDataset(), out, necktieOptions(5)).networks.front();
  const pl::TrainingData data = pl::loadTrainingData(necktieDataset(), pl::OffsetSpace::Root, {});
  const pl::TrainedModel model(out, data.garment);
  EXPECT_EQ(model.architecture(), pl::Architecture::Necktie);
  EXPECT_EQ(model.space(), pl::OffsetSpace::Root);
  // The regularisation error is measured after the epoch on the weights it saved (the train error is the mean over
  // the epoch's steps, as the weights moved).
  const double recorded = pc::readJson(out / "model.json")["regularisation_error_cm"].get<double>();
  EXPECT_NEAR(errorOf(model, data, data.regularisation), recorded, 1e-4);
  EXPECT_NEAR(recorded, report.epochs[report.bestEpoch - 1].regularisationErrorCm, 1e-9);
  EXPECT_NEAR(pc::readJson(out / "model.json")["train_error_cm"].get<double>(),
              report.epochs[report.bestEpoch - 1].trainErrorCm, 1e-9);
}

TEST(Train, PerChannelScalingIsFoldedIntoTheSavedWeights) {
  // Trained on scaled images, the saved model still predicts metres: it reloads to the error training measured.
  pl::TrainOptions options = necktieOptions(5);
  options.targetScaling = pl::TargetScaling::PerChannel;
  const fs::path out = pixelcloth::testing::freshDir("model");
  const pl::NetworkReport report = pl::train(necktieDataset(), out, options).networks.front();
  EXPECT_EQ(pc::readJson(out / "model.json")["target_scaling"], "per-channel");
  const pl::TrainingData data = pl::loadTrainingData(necktieDataset(), pl::OffsetSpace::Root, {});
  const pl::TrainedModel model(out, data.garment);
  const double recorded = report.epochs[report.bestEpoch - 1].regularisationErrorCm;
  EXPECT_NEAR(errorOf(model, data, data.regularisation), recorded, 1e-3 * recorded);
  // A different model from the unscaled run's, so the scaling did something.
  const fs::path plain = pixelcloth::testing::freshDir("plain");
  pl::train(necktieDataset(), plain, necktieOptions(5));
  EXPECT_GT(std::abs(errorOf(pl::TrainedModel(plain, data.garment), data, data.train) - recorded), 1e-3);
}

TEST(Train, AResumedRunEndsWithTheWeightsOfAnUninterruptedOne) {
  const fs::path whole = pixelcloth::testing::freshDir("whole"), split = pixelcloth::testing::freshDir("split");
  pl::train(necktieDataset(), whole, necktieOptions(4));
  const pl::NetworkReport first = pl::train(necktieDataset(), split, necktieOptions(2)).networks.front();
  EXPECT_EQ(first.resumedAt, 0);
  const pl::NetworkReport second = pl::train(necktieDataset(), split, necktieOptions(4)).networks.front();
  EXPECT_EQ(second.resumedAt, 2);
  ASSERT_EQ(second.epochs.size(), 4u);
  // The same weights: the same predictions, bit for bit, and the same log but for the seconds.
  const pl::TrainingData data = pl::loadTrainingData(necktieDataset(), pl::OffsetSpace::Root, {});
  const Eigen::MatrixXf inputs = data.inputs.topRows(3);
  const pl::TrainedModel a(whole, data.garment), b(split, data.garment);
  EXPECT_EQ(pc::readJson(whole / "model.json")["epoch"], pc::readJson(split / "model.json")["epoch"]);
  EXPECT_EQ(a.predict(inputs).front().values, b.predict(inputs).front().values);
  // Run again, finished: nothing to do; other settings: refused, naming the setting.
  EXPECT_EQ(pl::train(necktieDataset(), split, necktieOptions(4)).networks.front().resumedAt, 4);
  pl::TrainOptions other = necktieOptions(4);
  other.learningRate = 1e-2;
  const std::string message = inputErrorOf([&] { pl::train(necktieDataset(), split, other); });
  EXPECT_NE(message.find("learning_rate"), std::string::npos) << message;
  EXPECT_NE(message.find("checkpoint.tensors"), std::string::npos) << message;
}

TEST(Train, TheSchedulesDecayTheRateOverTheRun) {
  EXPECT_EQ(pl::scheduledRate(pl::Schedule::Constant, 1e-3, 99, 100), 1e-3);
  EXPECT_DOUBLE_EQ(pl::scheduledRate(pl::Schedule::Cosine, 1e-3, 0, 100), 1e-3);
  EXPECT_DOUBLE_EQ(pl::scheduledRate(pl::Schedule::Cosine, 1e-3, 50, 100), 0.5e-3);
  EXPECT_LT(pl::scheduledRate(pl::Schedule::Cosine, 1e-3, 99, 100), 1e-6);
  EXPECT_EQ(pl::scheduledRate(pl::Schedule::Step, 1e-3, 49, 100), 1e-3);
  EXPECT_DOUBLE_EQ(pl::scheduledRate(pl::Schedule::Step, 1e-3, 50, 100), 1e-4);
  EXPECT_DOUBLE_EQ(pl::scheduledRate(pl::Schedule::Step, 1e-3, 75, 100), 1e-5);
  EXPECT_EQ(pl::scheduleFromName("cosine", "test"), pl::Schedule::Cosine);
  EXPECT_NE(inputErrorOf([] { pl::scheduleFromName("linear", "train --schedule"); }).find("train --schedule"),
            std::string::npos);

  // A cosine run takes other steps than a constant one, and its length is one of its settings: a finished run is not
  // extended, and the schedule of a folder's run is not changed.
  pl::TrainOptions cosine = necktieOptions(3);
  cosine.schedule = pl::Schedule::Cosine;
  const fs::path decayed = pixelcloth::testing::freshDir("cosine"),
                 constant = pixelcloth::testing::freshDir("constant");
  pl::train(necktieDataset(), decayed, cosine);
  pl::train(necktieDataset(), constant, necktieOptions(3));
  const pl::TrainingData data = pl::loadTrainingData(necktieDataset(), pl::OffsetSpace::Root, {});
  const Eigen::MatrixXf inputs = data.inputs.topRows(2);
  EXPECT_NE(pl::TrainedModel(decayed, data.garment).predict(inputs).front().values,
            pl::TrainedModel(constant, data.garment).predict(inputs).front().values);
  pl::TrainOptions longer = cosine;
  longer.epochs = 5;
  const std::string extended = inputErrorOf([&] { pl::train(necktieDataset(), decayed, longer); });
  EXPECT_NE(extended.find("epochs"), std::string::npos) << extended;
  pl::TrainOptions stepped = necktieOptions(3);
  stepped.schedule = pl::Schedule::Step;
  const std::string changed = inputErrorOf([&] { pl::train(necktieDataset(), constant, stepped); });
  EXPECT_NE(changed.find("schedule"), std::string::npos) << changed;
}

TEST(Train, PatienceStopsARunThatNoLongerImproves) {
  // A learning rate far below the weights' float precision: the regularisation error stays where the first epoch left
  // it, so the run stops `patience` epochs after its best one, and a rerun of the folder stops where it stopped.
  pl::TrainOptions options = necktieOptions(12);
  options.model.architecture = pl::Architecture::FullyConnectedPca;
  options.model.pcaComponents = 8;
  options.learningRate = 1e-15;
  options.patience = 3;
  const fs::path out = pixelcloth::testing::freshDir("patience");
  const pl::NetworkReport stopped = pl::train(necktieDataset(), out, options).networks.front();
  EXPECT_TRUE(stopped.stoppedEarly);
  EXPECT_LT(stopped.epochs.size(), 12u);
  EXPECT_EQ(static_cast<int>(stopped.epochs.size()), stopped.bestEpoch + options.patience);
  EXPECT_EQ(pc::readJson(out / "model.json")["epoch"].get<int>(), stopped.bestEpoch);
  const pl::NetworkReport again = pl::train(necktieDataset(), out, options).networks.front();
  EXPECT_TRUE(again.stoppedEarly);
  EXPECT_EQ(again.epochs.size(), stopped.epochs.size());
  EXPECT_EQ(again.resumedAt, static_cast<int>(stopped.epochs.size()));
  options.patience = -1;
  EXPECT_NE(inputErrorOf([&] { options.validate(); }).find("patience"), std::string::npos);
}

namespace {
/// Tiny patch decoders of `patches`, batch 2, quiet.
pl::TrainOptions patchOptions(std::vector<int> patches, int epochs) {
  pl::TrainOptions options;
  options.model.architecture = pl::Architecture::Patch;
  options.model.width = 0.0625;
  options.epochs = epochs;
  options.batch = 2;
  options.patches = std::move(patches);
  return options;
}
}  // namespace

TEST(Train, PatchDecodersTrainInSubsetsIntoOneFolder) {
  pl::TrainOptions options = patchOptions({3, 7}, 1);
  const fs::path out = pixelcloth::testing::freshDir("patches");
  const pl::TrainReport first = pl::train(shirtDataset(), out, options);
  ASSERT_EQ(first.networks.size(), 2u);
  EXPECT_TRUE(fs::exists(out / "patch_03" / "model.tensors"));
  EXPECT_TRUE(fs::exists(out / "patch_07" / "model.tensors"));
  options.patches = {0};
  pl::train(shirtDataset(), out, options);
  const pl::TrainingData data = pl::loadTrainingData(shirtDataset(), pl::OffsetSpace::Local, {});
  const pl::TrainedModel model(out, data.garment);
  EXPECT_EQ(model.patches(), (std::vector<int>{0, 3, 7}));
  EXPECT_EQ(model.engine(), pl::Engine::OneDnn);
  const std::vector<pl::NetworkPrediction> predicted = model.predict(data.inputs.topRows(2));
  ASSERT_EQ(predicted.size(), 3u);
  // The oneDNN engine predicts what LibTorch's modules do.
  const std::vector<pl::NetworkPrediction> reference =
      pl::TrainedModel(out, data.garment, pl::Engine::LibTorch).predict(data.inputs.topRows(2));
  ASSERT_EQ(reference.size(), 3u);
  for (size_t k = 0; k < reference.size(); ++k) {
    EXPECT_EQ(predicted[k].vertices, reference[k].vertices);
    EXPECT_GT(reference[k].values.cwiseAbs().maxCoeff(), 0);  // trained: no longer the zero start
    EXPECT_LE((predicted[k].values - reference[k].values).cwiseAbs().maxCoeff(),
              1e-5 * reference[k].values.cwiseAbs().maxCoeff())
        << "patch " << reference[k].patch;
  }
  // Each crop covers its patch and a band of its neighbours: more vertices than the patch has.
  const std::vector<pixelcloth::patches::Patch> patchList = pixelcloth::patches::garmentPatches(data.garment);
  for (const pl::NetworkPrediction& p : predicted) {
    EXPECT_EQ(p.values.rows(), 2);
    EXPECT_EQ(p.values.cols(), 3 * static_cast<int>(p.vertices.size()));
    EXPECT_GT(p.vertices.size(), patchList[p.patch].vertices.size()) << "patch " << p.patch;
    for (int v : patchList[p.patch].vertices)
      EXPECT_TRUE(std::binary_search(p.vertices.begin(), p.vertices.end(), v)) << "patch " << p.patch;
  }
  options.patches = {28};
  EXPECT_NE(inputErrorOf([&] { pl::train(shirtDataset(), out, options); }).find("patches 0 to 27"), std::string::npos);
}

TEST(Train, PatchDecodersTrainedTwoAtOnceEqualThoseTrainedOneAfterAnother) {
  pl::TrainOptions options = patchOptions({1, 4, 9}, 2);
  options.threads = 2;
  options.networksAtOnce = 2;  // one thread each
  const fs::path together = pixelcloth::testing::freshDir("together"), apart = pixelcloth::testing::freshDir("apart");
  const pl::TrainReport a = pl::train(shirtDataset(), together, options);
  options.threads = 1;
  options.networksAtOnce = 1;
  const pl::TrainReport b = pl::train(shirtDataset(), apart, options);
  ASSERT_EQ(a.networks.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(a.networks[k].patch, options.patches[k]);  // reported in job order
    EXPECT_EQ(a.networks[k].epochs.back().trainErrorCm, b.networks[k].epochs.back().trainErrorCm);
  }
  const pl::TrainingData data = pl::loadTrainingData(shirtDataset(), pl::OffsetSpace::Local, {});
  const std::vector<pl::NetworkPrediction> x = pl::TrainedModel(together, data.garment).predict(data.inputs.topRows(2)),
                                           y = pl::TrainedModel(apart, data.garment).predict(data.inputs.topRows(2));
  for (size_t k = 0; k < 3; ++k) EXPECT_EQ(x[k].values, y[k].values) << "patch " << x[k].patch;
}

TEST(Train, TheBaselinesTrainInEachSpace) {
  for (const pl::OffsetSpace space : {pl::OffsetSpace::Local, pl::OffsetSpace::Root, pl::OffsetSpace::Positions}) {
    for (const pl::Architecture architecture : {pl::Architecture::FullyConnected, pl::Architecture::FullyConnectedPca}) {
      pl::TrainOptions options = necktieOptions(2);
      options.model.architecture = architecture;
      options.space = space;
      const fs::path out = pixelcloth::testing::freshDir(std::string(pl::offsetSpaceName(space)) + "-" +
                                                         pl::architectureName(architecture));
      const pl::NetworkReport report = pl::train(necktieDataset(), out, options).networks.front();
      const pl::TrainingData data = pl::loadTrainingData(necktieDataset(), space, {});
      const pl::TrainedModel model(out, data.garment);
      EXPECT_EQ(model.space(), space);
      EXPECT_NEAR(errorOf(model, data, data.regularisation), report.epochs[report.bestEpoch - 1].regularisationErrorCm,
                  1e-3)
          << pl::offsetSpaceName(space) << " " << pl::architectureName(architecture);
    }
  }
  // With every component, the train split's PCA reproduces its targets.
  const pl::TrainingData data = pl::loadTrainingData(necktieDataset(), pl::OffsetSpace::Root, {});
  Eigen::MatrixXf targets(data.train.size(), 3 * data.garment.mesh.numVertices());
  for (size_t k = 0; k < data.train.size(); ++k)
    for (int v = 0; v < data.garment.mesh.numVertices(); ++v)
      targets.block<1, 3>(k, 3 * v) = data.values[data.train[k]].row(v);
  const pl::PcaBasis basis = pl::fitPca(targets, static_cast<int>(data.train.size()));
  EXPECT_LT((basis.reconstruct(basis.project(targets)) - targets).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(Train, ALearningCurveUsesTheFirstSamplesOfTheTrainSplitOnly) {
  // fc-pca asks for 8 components; from the first 3 of the 8 train samples its PCA can fit only 3.
  pl::TrainOptions options = necktieOptions(2);
  options.model.architecture = pl::Architecture::FullyConnectedPca;
  options.model.pcaComponents = 8;
  options.trainSamples = 3;
  const fs::path out = pixelcloth::testing::freshDir("model");
  pl::train(necktieDataset(), out, options);
  const nlohmann::json sidecar = pc::readJson(out / "model.json");
  EXPECT_EQ(sidecar["train_samples"].get<int>(), 3);
  EXPECT_EQ(sidecar["pca_components"].get<int>(), 3);
  // More than the split holds is refused, naming the dataset; another subset does not resume this run.
  options.trainSamples = 9;
  const std::string tooMany =
      inputErrorOf([&] { pl::train(necktieDataset(), pixelcloth::testing::freshDir("more"), options); });
  EXPECT_NE(tooMany.find("--train-samples 9"), std::string::npos) << tooMany;
  EXPECT_NE(tooMany.find("8 samples in its train split"), std::string::npos) << tooMany;
  options.trainSamples = -1;
  const std::string negative =
      inputErrorOf([&] { pl::train(necktieDataset(), pixelcloth::testing::freshDir("less"), options); });
  EXPECT_NE(negative.find("-1 train samples"), std::string::npos) << negative;
  options.trainSamples = 4;
  options.model.pcaComponents = 3;
  const std::string other = inputErrorOf([&] { pl::train(necktieDataset(), out, options); });
  EXPECT_NE(other.find("train_samples"), std::string::npos) << other;
}

TEST(Train, WrongModelsAndDamagedCheckpointsAreRefused) {
  pl::TrainOptions whole = necktieOptions(1);
  whole.model.architecture = pl::Architecture::Whole;
  const fs::path out = pixelcloth::testing::freshDir("model");
  const std::string mismatch = inputErrorOf([&] { pl::train(necktieDataset(), out, whole); });
  EXPECT_NE(mismatch.find("necktie"), std::string::npos) << mismatch;
  EXPECT_FALSE(fs::exists(out / "model.tensors"));

  pl::train(necktieDataset(), out, necktieOptions(1));
  const pg::Garment tie = pd::datasetGarment(pd::readDatasetInfo(necktieDataset()));
  // Truncated weights.
  const std::string bytes = pc::readTextFile(out / "model.tensors");
  pc::writeTextAtomically(out / "model.tensors", bytes.substr(0, bytes.size() / 2));
  const std::string truncated = inputErrorOf([&] { pl::TrainedModel(out, tie); });
  EXPECT_NE(truncated.find("model.tensors"), std::string::npos) << truncated;
  // Weights of another width.
  pc::writeTextAtomically(out / "model.tensors", bytes);
  nlohmann::json sidecar = pc::readJson(out / "model.json");
  sidecar["width"] = 0.5;
  pc::writeJson(out / "model.json", sidecar);
  const std::string wider = inputErrorOf([&] { pl::TrainedModel(out, tie); });
  EXPECT_NE(wider.find("width 0.5"), std::string::npos) << wider;
  // A model of another garment.
  sidecar["width"] = 0.25;
  pc::writeJson(out / "model.json", sidecar);
  const std::string shirt = inputErrorOf([&] { pl::TrainedModel(out, pd::datasetGarment(pd::readDatasetInfo(shirtDataset()))); });
  EXPECT_NE(shirt.find("not of this tshirt"), std::string::npos) << shirt;
  // A truncated training checkpoint: the run says so instead of starting over silently.
  const std::string checkpoint = pc::readTextFile(out / "checkpoint.tensors");
  pc::writeTextAtomically(out / "checkpoint.tensors", checkpoint.substr(0, checkpoint.size() / 3));
  const std::string damaged = inputErrorOf([&] { pl::train(necktieDataset(), out, necktieOptions(2)); });
  EXPECT_NE(damaged.find("checkpoint.tensors"), std::string::npos) << damaged;
}
