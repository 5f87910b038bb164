// data::rebaseDataset: the same samples on another body, for the paper's body-shape and skinning experiments.
#include <gtest/gtest.h>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/data/dataset.h"
#include "support/synthetic_dataset.h"
#include "support/test_util.h"

namespace pb = pixelcloth::body;
namespace pc = pixelcloth::core;
namespace pd = pixelcloth::data;
namespace pt = pixelcloth::testing;
namespace fs = std::filesystem;

namespace {

const pb::Body& thickerCoarseMannequin() {
  static const pb::Body body = [] {
    pb::MannequinOptions options;
    options.edgeLength = 0.02;
    options.shape = 1.0;
    return pb::makeMannequin(options);
  }();
  return body;
}

double meanNormalOffset(const pd::Dataset& dataset) {
  double sum = 0;
  for (int r = 0; r < dataset.rows(); ++r) sum += dataset.offsetsOf(r).col(2).cast<double>().mean();
  return sum / dataset.rows();
}

}  // namespace

TEST(DatasetRebase, KeepsPositionsPosesAndSplitAndRecomputesOffsetsOnTheNewBody) {
  const fs::path source = pt::syntheticDataset("rebase", "necktie", 10);
  const fs::path out = pt::freshDir("rebased") / "thicker";
  const nlohmann::json description = {{"kind", "mannequin"}, {"shape", 1.0}, {"edge_length", 0.02}};
  pd::rebaseDataset(source, thickerCoarseMannequin(), description, out);

  // The new folder passes every check, offsets recomputed from positions on its own body for every sample.
  pd::DatasetCheckOptions check;
  check.strongSamples = 10;
  EXPECT_EQ(pd::checkDataset(out, check).strongSamples, 10);

  const pd::Dataset before = pd::openDataset(source), after = pd::openDataset(out);
  ASSERT_EQ(after.rows(), before.rows());
  EXPECT_EQ(after.positions.bytes, before.positions.bytes);
  EXPECT_TRUE(after.poses == before.poses);
  EXPECT_EQ(after.split, before.split);
  EXPECT_EQ(after.info.settings.seed, before.info.settings.seed);
  // On a body of more girth the cloth sits closer to the skin: the normal offsets shrink.
  EXPECT_LT(meanNormalOffset(after), meanNormalOffset(before) - 0.003)
      << meanNormalOffset(after) << " m vs " << meanNormalOffset(before) << " m";
  const nlohmann::json body = after.info.manifest["body"];
  EXPECT_EQ(body["shape"], 1.0);
  EXPECT_EQ(body["rebased_from"]["body"], before.info.settings.body);
  EXPECT_EQ(body["rebased_from"]["manifest_crc32"].get<std::uint32_t>(), pd::fileCrc32(source / "manifest.json"));
  EXPECT_TRUE(after.info.manifest["settings"].contains("rebased_stats"));
}

TEST(DatasetRebase, OntoItsOwnBodyTheOffsetsBarelyMove) {
  const fs::path source = pt::syntheticDataset("rebase-same", "necktie", 6);
  const fs::path out = pt::freshDir("same") / "same";
  pd::rebaseDataset(source, pt::coarseMannequin(), {{"kind", "mannequin"}, {"edge_length", 0.02}}, out);
  const pd::Dataset before = pd::openDataset(source), after = pd::openDataset(out);
  double worst = 0;
  for (int r = 0; r < after.rows(); ++r)
    worst = std::max(worst, double((after.offsetsOf(r) - before.offsetsOf(r)).rowwise().norm().maxCoeff()));
  // The same body and rest positions give the same closest points; only the u-direction is carried through the old
  // frames, so du and dv may turn a little.
  EXPECT_LT(worst, 1e-4) << worst;
}

TEST(DatasetRebase, ABodyWithOtherJointsIsRefusedNamingBoth) {
  const fs::path source = pt::syntheticDataset("rebase-joints", "necktie", 4);
  pb::Body body = pt::coarseMannequin();
  body.skeleton.names[3] = "tail";
  const fs::path out = pt::freshDir("joints") / "out";
  const std::string message = pt::inputErrorOf([&] { pd::rebaseDataset(source, body, {{"kind", "test"}}, out); });
  EXPECT_EQ(message.rfind("dataset rebase: the body's skeleton has joints ", 0), 0u) << message;
  EXPECT_NE(message.find("tail"), std::string::npos) << message;
  EXPECT_NE(message.find(source.string()), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(out));
}
