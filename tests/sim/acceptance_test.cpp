// The paper's acceptance test over the sampler's poses: most simulated T-shirt poses are kept, and raised arms (the
// poses a tight armhole used to lose) are kept about as often as the rest.
#include <gtest/gtest.h>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/sim/garment_sim.h"
#include "pixelcloth/sim/generate.h"

namespace pixelcloth::sim {
namespace {

TEST(SampledTShirtPoses, MostPassThePapersAreaTestRaisedArmsIncluded) {
  const body::Body body = body::makeMannequin();
  const garment::Garment shirt = garment::makeTShirt();
  const cage::Dressing dressing = cage::dressGarment(body, cage::bodyCage(body), shirt, cage::garmentCage(shirt));
  constexpr int kPoses = 96;
  std::vector<body::Pose> poses;
  for (int i = 0; i < kPoses; ++i) poses.push_back(samplePose(body, garment::GarmentTraits{}, 7, i, 0));
  const std::vector<data::SampleStats> stats = simulatePoses(body, shirt, dressing, poses, {}, 0);

  int kept = 0, raised = 0, raisedKept = 0;
  for (int i = 0; i < kPoses; ++i) {
    const bool ok = stats[i].rejection == data::Rejection::None;
    kept += ok;
    if (poses[i].toEulerDegrees()(5, 2) > 30) {  // l_arm raised more than 30 degrees above the T-pose
      ++raised;
      raisedKept += ok;
    }
    if (ok) {
      EXPECT_GE(stats[i].minAreaRatio, 0.25) << "pose " << i;
      EXPECT_LE(stats[i].maxAreaRatio, 2.0) << "pose " << i;
      EXPECT_LE(stats[i].maxPenetration, 0.002) << "pose " << i;
    }
  }
  // 92 measured (86 without the extra rounds; docs/simulation.md has the rates over many seeds). Any change of the
  // solver moves this by a few poses either way, so the test guards the rate of 85% (the shirt with the
  // 0.23 m armpit and 0.19 m sleeve hem kept 81 without extra rounds, the old tight armhole 73) rather than the last
  // pose of it.
  EXPECT_GE(kept, 82) << "of " << kPoses << " sampled poses (85% is the goal)";
  ASSERT_GE(raised, 16);
  EXPECT_GT(2 * raisedKept, raised) << raisedKept << " of " << raised << " poses with the left arm raised kept";

  // The extra rounds only ever continue a pose that failed: one that passed on schedule is the same sample without
  // them, and every pose they win back is a later iterate that passes the same test.
  SimulationOptions scheduleOnly;
  scheduleOnly.extraIterations = 0;
  const std::vector<data::SampleStats> plain = simulatePoses(body, shirt, dressing, poses, scheduleOnly, 0);
  int keptPlain = 0, wonBack = 0;
  for (int i = 0; i < kPoses; ++i) {
    EXPECT_EQ(plain[i].extraRounds, 0) << "pose " << i;
    if (plain[i].rejection == data::Rejection::None) {
      ++keptPlain;
      EXPECT_EQ(stats[i].extraRounds, 0) << "pose " << i;
      EXPECT_EQ(stats[i].iterations, plain[i].iterations) << "pose " << i;
      EXPECT_EQ(stats[i].minAreaRatio, plain[i].minAreaRatio) << "pose " << i;
      EXPECT_EQ(stats[i].maxAreaRatio, plain[i].maxAreaRatio) << "pose " << i;
    } else {
      EXPECT_GE(stats[i].extraRounds, 1) << "pose " << i;
      EXPECT_LE(stats[i].extraRounds, 3) << "pose " << i;
      EXPECT_GT(stats[i].iterations, plain[i].iterations) << "pose " << i;
      wonBack += stats[i].rejection == data::Rejection::None;
    }
  }
  EXPECT_EQ(kept, keptPlain + wonBack);
  EXPECT_GT(wonBack, 0) << "no failed pose passed after relaxing on";
}

}  // namespace
}  // namespace pixelcloth::sim
