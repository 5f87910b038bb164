// Training an image decoder on a small necktie dataset: it learns its training samples, its checkpoint reloads to
// the same predictions, and wrong models and damaged checkpoints are refused.
#include "pixelcloth/learn/train.h"

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
#include "support/test_util.h"

namespace fs = std::filesystem;
namespace pb = pixelcloth::body;
namespace pc = pixelcloth::core;
namespace pd = pixelcloth::data;
namespace pg = pixelcloth::garment;
namespace pl = pixelcloth::learn;
using pixelcloth::testing::inputErrorOf;

namespace {

/// 10 necktie samples on the coarse mannequin: small centre-line poses, the rest offsets plus a sample's own bulge.
const fs::path& necktieDataset() {
  static const fs::path folder = [] {
    const fs::path dir =
        fs::temp_directory_path() / "pixelcloth-tests" / ("learn-necktie." + std::to_string(::getpid()));
    fs::remove_all(dir);
    const pb::Body& body = pixelcloth::testing::coarseMannequin();
    const pg::Garment tie = pg::makeNecktie();
    const Eigen::MatrixX3d rest = tie.mesh.V;
    Eigen::MatrixX3d u = Eigen::MatrixX3d::Zero(rest.rows(), 3);
    u.col(0).setOnes();
    const pg::Embedding embedding = pg::embedClosest(body.mesh.V, body.mesh.F, rest, u);
    const Eigen::MatrixX3d restOffsets =
        pg::offsetsFromPositions(pg::embeddedFrames(body.mesh.V, body.mesh.F, embedding), rest);
    pd::DatasetSettings settings;
    settings.garment = "necktie";
    settings.poseSize = pb::kNecktiePoseSize;
    settings.vertexCount = tie.mesh.numVertices();
    settings.seed = 5;
    settings.count = 10;
    settings.body = {{"kind", "mannequin"}, {"edge_length", 0.02}};
    pd::DatasetWriter writer(dir, settings, body, tie, rest, embedding);
    for (int i : writer.pending()) {
      const Eigen::VectorXf vector = pb::randomPose(40 + i, 0.2).toVector().head(pb::kNecktiePoseSize);
      const pb::Pose pose = pb::Pose::fromLeading(vector);
      Eigen::MatrixX3d offsets = restOffsets;
      for (int v = 0; v < offsets.rows(); ++v) offsets(v, 2) += 0.01 * std::sin(8 * rest(v, 1) + i);
      const pg::EmbeddedFrames frames = pg::embeddedFrames(body.posedVertices(pose), body.mesh.F, embedding);
      pd::Sample sample;
      sample.pose = vector;
      sample.positions = pg::positionsFromOffsets(frames, offsets).cast<float>();
      sample.offsets = pg::offsetsFromPositions(frames, sample.positions.cast<double>()).cast<float>();
      writer.add(i, sample);
    }
    writer.finish();
    return dir;
  }();
  return folder;
}

pl::TrainOptions necktieOptions(int epochs) {
  pl::TrainOptions options;
  options.model.architecture = pl::Architecture::Necktie;
  options.model.width = 0.25;
  options.epochs = epochs;
  options.batch = 4;
  options.learningRate = 2e-3;
  options.seed = 1;
  options.quiet = true;
  return options;
}

}  // namespace

TEST(Train, ANecktieDecoderLearnsItsTrainingSamples) {
  const fs::path out = pixelcloth::testing::freshDir("model");
  const pl::TrainReport report = pl::trainImageModel(necktieDataset(), out, necktieOptions(150));
  ASSERT_EQ(report.epochs.size(), 150u);
  const double first = report.epochs.front().trainErrorCm, last = report.epochs.back().trainErrorCm;
  std::cout << "[necktie width 0.25, 8 samples] train error " << first << " cm after epoch 1, " << last
            << " cm after 150; regularisation " << report.epochs.back().regularisationErrorCm << " cm\n";
  // Falling fast; the bar (under 0.05 cm) needs longer training than a unit test should take.
  EXPECT_LT(last, 1.5);
  EXPECT_LT(last, first / 10);
  EXPECT_GE(report.bestEpoch, 1);
  for (const char* file : {"model.pt", "model.json", "log.csv"}) EXPECT_TRUE(fs::exists(out / file)) << file;
  // log.csv: a header and one row per epoch.
  std::ifstream log(out / "log.csv");
  int lines = 0;
  for (std::string line; std::getline(log, line);) ++lines;
  EXPECT_EQ(lines, 151);
}

TEST(Train, TheCheckpointReloadsToItsRecordedError) {
  const fs::path out = pixelcloth::testing::freshDir("model");
  const pl::TrainReport report = pl::trainImageModel(necktieDataset(), out, necktieOptions(5));
  const pl::Model model = pl::loadModel(out);
  EXPECT_EQ(model.spec().architecture, pl::Architecture::Necktie);
  const pd::Dataset dataset = pd::openDataset(necktieDataset());
  const std::vector<int> train = dataset.rowsOf(pd::Split::Train);
  Eigen::MatrixXf poses(train.size(), pb::kNecktiePoseSize);
  for (size_t k = 0; k < train.size(); ++k) poses.row(k) = dataset.pose(train[k]).transpose();
  const Eigen::MatrixXf predicted = pl::predictOffsets(model, necktieDataset(), poses);
  double error = 0;
  for (size_t k = 0; k < train.size(); ++k) {
    Eigen::MatrixXf offsets(dataset.vertexCount(), 3);
    for (int v = 0; v < dataset.vertexCount(); ++v) offsets.row(v) = predicted.block<1, 3>(k, 3 * v);
    error += (offsets - dataset.offsetsOf(train[k])).rowwise().norm().mean();
  }
  const double recorded = pc::readJson(out / "model.json")["train_error_cm"].get<double>();
  EXPECT_NEAR(100 * error / train.size(), recorded, 1e-4);
  EXPECT_NEAR(recorded, report.epochs[report.bestEpoch - 1].trainErrorCm, 1e-9);
}

TEST(Train, WrongModelsAndDamagedCheckpointsAreRefused) {
  pl::TrainOptions whole = necktieOptions(1);
  whole.model.architecture = pl::Architecture::Whole;
  const fs::path out = pixelcloth::testing::freshDir("model");
  const std::string mismatch = inputErrorOf([&] { pl::trainImageModel(necktieDataset(), out, whole); });
  EXPECT_NE(mismatch.find("(6, 256, 256)"), std::string::npos) << mismatch;
  EXPECT_NE(mismatch.find("necktie"), std::string::npos) << mismatch;
  EXPECT_FALSE(fs::exists(out / "model.pt"));

  pl::trainImageModel(necktieDataset(), out, necktieOptions(1));
  // Truncated weights.
  const std::string bytes = pc::readTextFile(out / "model.pt");
  pc::writeTextAtomically(out / "model.pt", bytes.substr(0, bytes.size() / 2));
  const std::string truncated = inputErrorOf([&] { pl::loadModel(out); });
  EXPECT_NE(truncated.find("model.pt"), std::string::npos) << truncated;
  // Weights of another width.
  pc::writeTextAtomically(out / "model.pt", bytes);
  nlohmann::json sidecar = pc::readJson(out / "model.json");
  sidecar["width"] = 0.5;
  pc::writeJson(out / "model.json", sidecar);
  const std::string wider = inputErrorOf([&] { pl::loadModel(out); });
  EXPECT_NE(wider.find("width 0.5"), std::string::npos) << wider;
}
