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

TEST(PoseFigures, BarsGrowWithTheirShareOfPoses) {
  // Every pose at rest: each movable angle has one full-height grey bar (the bin holding 0).
  const std::vector<body::Pose> rest(10, body::Pose::identity());
  const core::RgbImage restOnly = renderJointHistograms(rest, {});
  const int greyRest = countColor(restOnly, {170, 170, 170});
  EXPECT_GT(greyRest, 0);
  // Half the poses moved: the rest bins drop to half height and other bins appear, so less grey in all.
  std::vector<body::Pose> mixed = rest;
  for (int k = 0; k < 10; ++k) {
    Eigen::Matrix<double, 10, 3> degrees = Eigen::Matrix<double, 10, 3>::Zero();
    degrees(5, 2) = 40.0 + k;  // l_arm z
    mixed.push_back(body::Pose::fromEulerDegrees(degrees));
  }
  const core::RgbImage half = renderJointHistograms(mixed, {});
  EXPECT_NE(countColor(half, {170, 170, 170}), greyRest);
  // The kept poses show in blue (blended over grey).
  const core::RgbImage withAfter = renderJointHistograms(mixed, rest);
  EXPECT_NE(withAfter.pixels, half.pixels);
  EXPECT_NE(testing::inputErrorOf([&] { renderJointHistograms(rest, rest, 1); }).find("bins"), std::string::npos);
}

}  // namespace
}  // namespace pixelcloth::viz
