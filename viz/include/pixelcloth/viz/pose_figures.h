#pragma once

#include <string>
#include <vector>

#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/image.h"

namespace pixelcloth::viz {

/// One stage of pose filtering, as renderJointHistograms draws it.
struct PoseStage {
  std::string label;  ///< legend text, e.g. "drawn"
  std::vector<body::Pose> poses;
  core::Color color;
};

/// Joint-angle histograms as in the paper's pose-sampling figure: one panel per joint and Euler angle (x twist, z,
/// y; degrees over the joint's limits, `bins` bins). Each stage's bars are drawn narrower over the previous stage's,
/// all in counts on one scale (the tallest bin of any stage), so the drop from one colour to the next in a bin is
/// what that filtering stage removed there. Titles name joint and axis; the legend gives each stage's count.
core::RgbImage renderJointHistograms(const std::vector<PoseStage>& stages, int bins = 18);

/// How many poses of one joint-angle bin survive a filtering stage.
struct JointBinLoss {
  std::string joint;  ///< e.g. "l_arm"
  std::string axis;   ///< "x", "y" or "z"
  double lowerDegrees = 0, upperDegrees = 0;
  int before = 0, after = 0;
  double keptFraction() const { return before > 0 ? static_cast<double>(after) / before : 1.0; }
};

/// Over every movable joint angle and bin (as renderJointHistograms bins them) holding at least `minCount` of the
/// poses `before`, the bin that keeps the smallest share of them in `after`. `after` is meant to be a subset of
/// `before`. Returns a bin with before = 0 when no bin holds `minCount` poses.
JointBinLoss worstJointBin(const std::vector<body::Pose>& before, const std::vector<body::Pose>& after, int bins = 18,
                           int minCount = 10);

}  // namespace pixelcloth::viz
