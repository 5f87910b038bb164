// The appendix's pose sampler: its distributions, limits, seeding and pruning.
#include "pixelcloth/sim/pose_sampler.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pixelcloth/body/body.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/sim/generate.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace ps = pixelcloth::sim;
namespace pb = pixelcloth::body;
namespace fs = std::filesystem;

namespace {
const pb::Body& body() {
  static const pb::Body b = [] {
    pb::MannequinOptions options;
    options.edgeLength = 0.015;
    return pb::makeMannequin(options);
  }();
  return b;
}
constexpr double kDegree = M_PI / 180.0;
}  // namespace

TEST(PoseSampler, DistributionsFollowTheAppendix) {
  ps::PoseSamplerOptions options;
  options.seed = 11;
  ps::PoseSampler sampler(body(), options);
  const int n = 4000;
  double sinAltitude = 0, azimuth = 0, spineFlexion = 0, spineExtension = 0;
  int flexed = 0, extended = 0;
  for (int i = 0; i < n; ++i) {
    pb::Pose pose = sampler.draw();
    EXPECT_TRUE(pose.withinLimits(1e-6));
    Eigen::Matrix<double, 10, 3> e = pose.toEulerDegrees();
    sinAltitude += std::sin(e(5, 2) * kDegree) / n;  // l_arm altitude
    azimuth += e(5, 1) / n;                          // l_arm azimuth
    if (e(1, 0) > 0) {
      spineFlexion += e(1, 0);
      ++flexed;
    } else if (e(1, 0) < 0) {
      spineExtension += e(1, 0);
      ++extended;
    }
  }
  const pb::JointLimits& arm = pb::jointLimits("l_arm");
  // Altitude uniform in sine space: the mean of sin(z) is the middle of [sin(lo), sin(hi)] (0 for +-90 degrees).
  EXPECT_NEAR(sinAltitude, 0.5 * (std::sin(arm.lower.z() * kDegree) + std::sin(arm.upper.z() * kDegree)), 0.03);
  // Azimuth uniform: mean at the middle of its range.
  EXPECT_NEAR(azimuth, 0.5 * (arm.lower.y() + arm.upper.y()), 4.0);
  // Centre line: two half-normals with sigma = 0.5 x each side's limit, chosen with equal probability; the mean of a
  // half-normal (clamped at 2 sigma) is about 0.75 sigma.
  const pb::JointLimits& spine = pb::jointLimits("spine");
  EXPECT_NEAR(static_cast<double>(flexed) / n, 0.5, 0.03);
  EXPECT_NEAR(spineFlexion / flexed, 0.5 * spine.upper.x() * 0.75, 0.1 * spine.upper.x());
  EXPECT_NEAR(spineExtension / extended, 0.5 * spine.lower.x() * 0.75, 0.1 * -spine.lower.x());
}

TEST(PoseSampler, SeededAndPruned) {
  ps::PoseSamplerOptions options;
  options.seed = 5;
  ps::PoseSampler a(body(), options), b(body(), options);
  std::vector<pb::Pose> first = a.sample(40), second = b.sample(40);
  for (size_t i = 0; i < first.size(); ++i) EXPECT_EQ(first[i].toVector(), second[i].toVector());
  for (const pb::Pose& pose : first) EXPECT_FALSE(a.armInsideTorso(pose));
  EXPECT_EQ(a.stats().accepted, 40);
  RecordProperty("rejected_of_40", std::to_string(a.stats().rejectedArmInsideTorso));
}

TEST(PoseSampler, AnArmThroughTheChestIsPrunedAndTheRestPoseIsNot) {
  ps::PoseSampler sampler(body());
  EXPECT_FALSE(sampler.armInsideTorso(pb::Pose::identity()));
  Eigen::Matrix<double, 10, 3> degrees = Eigen::Matrix<double, 10, 3>::Zero();
  degrees(5, 1) = 180;  // the left arm swung round to point across the chest, through the torso
  degrees(5, 2) = -15;
  EXPECT_TRUE(sampler.armInsideTorso(pb::Pose::fromEulerDegrees(degrees)));
  degrees.setZero();
  degrees(5, 2) = 60;  // raised: outside
  EXPECT_FALSE(sampler.armInsideTorso(pb::Pose::fromEulerDegrees(degrees)));
}

// A simulated dataset's draws made again from its seed: the sampler's raw draws, those its prune let through to the
// simulation and the samples' own poses, in the counts its manifest tallied.
TEST(PoseSampler, ADatasetsDrawsAreMadeAgainFromItsSeedInTheCountsItsManifestTallied) {
  const fs::path folder = pixelcloth::testing::freshDir("draws");
  ps::GenerateOptions options;
  options.count = 6;
  options.seed = 3;
  options.threads = 2;
  options.mannequinEdge = 0.015;
  ps::generateDataset(folder, options);
  const pixelcloth::data::Dataset dataset = pixelcloth::data::openDataset(folder);
  const pixelcloth::data::DatasetStats& tally = dataset.info.stats;
  const auto pruned = tally.rejected.find("arm_inside_torso");
  const int prunedDraws = pruned == tally.rejected.end() ? 0 : pruned->second;
  const pb::Body body = pixelcloth::data::loadDatasetBody(folder);
  const auto traits = pixelcloth::data::datasetGarment(dataset.info).traits;
  const ps::SampledPoses poses = ps::datasetPoseDraws(dataset, body, traits);
  ASSERT_EQ(poses.kept.size(), 6u);
  for (int r = 0; r < 6; ++r) EXPECT_EQ(poses.kept[r].toVector(), dataset.pose(r)) << r;
  EXPECT_EQ(static_cast<int>(poses.simulated.size()), tally.simulated());
  EXPECT_EQ(static_cast<int>(poses.drawn.size()), static_cast<int>(poses.simulated.size()) + prunedDraws);
  EXPECT_GT(prunedDraws, 0) << "this seed's draws include arms inside the torso";

  // Another seed's sampler does not draw these poses.
  pixelcloth::data::Dataset other = dataset;
  other.info.settings.seed = 4;
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] {
              ps::datasetPoseDraws(other, body, traits, 5);
            }).find("none of the sampler's first 5 attempts from seed 4"),
            std::string::npos);
}
