#include "pixelcloth/viz/pose_figures.h"

#include <gtest/gtest.h>

#include "support/test_util.h"

namespace pixelcloth::viz {
namespace {

/// Counts pixels of exactly this colour.
int countColor(const core::RgbImage& image, core::Color color) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (p[0] == color[0] && p[1] == color[1] && p[2] == color[2]) ++n;
    }
  return n;
}

const core::Color kGrey = {170, 170, 170}, kBlue = {40, 100, 200};

/// Poses at rest except l_arm z, set to each of `degrees`.
std::vector<body::Pose> armRaised(const std::vector<double>& degrees) {
  std::vector<body::Pose> poses;
  for (double d : degrees) {
    Eigen::Matrix<double, 10, 3> euler = Eigen::Matrix<double, 10, 3>::Zero();
    euler(5, 2) = d;
    poses.push_back(body::Pose::fromEulerDegrees(euler));
  }
  return poses;
}

TEST(PoseFigures, BarsGrowWithTheirCountOfPoses) {
  // Every pose at rest: each movable angle has one full-height grey bar (the bin holding 0).
  const std::vector<body::Pose> rest(10, body::Pose::identity());
  const core::RgbImage restOnly = renderJointHistograms({{"drawn", rest, kGrey}});
  const int greyRest = countColor(restOnly, kGrey);
  EXPECT_GT(greyRest, 0);
  // Ten more poses with the arm raised: the l_arm z panel gains a bar, every other panel keeps its one full bar.
  std::vector<body::Pose> mixed = rest;
  for (const body::Pose& pose : armRaised({40, 41, 42, 43, 44, 45, 46, 47, 48, 49})) mixed.push_back(pose);
  const core::RgbImage more = renderJointHistograms({{"drawn", mixed, kGrey}});
  EXPECT_GT(countColor(more, kGrey), greyRest);
  // A later stage draws narrower bars over the earlier ones, as tall as its own counts.
  const core::RgbImage stages = renderJointHistograms({{"drawn", mixed, kGrey}, {"kept", rest, kBlue}});
  EXPECT_GT(countColor(stages, kBlue), 0);
  EXPECT_LT(countColor(stages, kGrey), countColor(more, kGrey));
  EXPECT_NE(testing::inputErrorOf([&] { renderJointHistograms({{"drawn", rest, kGrey}}, 1); }).find("bins"),
            std::string::npos);
  EXPECT_NE(testing::inputErrorOf([&] { renderJointHistograms({}); }).find("stages"), std::string::npos);
}

TEST(PoseFigures, WorstBinIsTheOneThatLosesTheLargestShare) {
  // 12 poses at rest, 12 with the arm at 60 degrees; filtering keeps all at rest and 3 of the raised ones.
  std::vector<body::Pose> before(12, body::Pose::identity()), after(12, body::Pose::identity());
  const std::vector<body::Pose> raised = armRaised(std::vector<double>(12, 60.0));
  before.insert(before.end(), raised.begin(), raised.end());
  after.insert(after.end(), raised.begin(), raised.begin() + 3);
  const JointBinLoss worst = worstJointBin(before, after);
  EXPECT_EQ(worst.joint, "l_arm");
  EXPECT_EQ(worst.axis, "z");
  EXPECT_EQ(worst.before, 12);
  EXPECT_EQ(worst.after, 3);
  EXPECT_LE(worst.lowerDegrees, 60.0);
  EXPECT_GT(worst.upperDegrees, 60.0);
  EXPECT_DOUBLE_EQ(worst.keptFraction(), 0.25);
  // Bins with fewer poses than minCount are not considered: no bin holds more than all 24.
  EXPECT_EQ(worstJointBin(before, after, 18, 25).before, 0);
  // Nothing lost: every bin keeps all.
  EXPECT_DOUBLE_EQ(worstJointBin(before, before).keptFraction(), 1.0);
}

}  // namespace
}  // namespace pixelcloth::viz
