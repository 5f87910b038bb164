#pragma once

#include <string>
#include <vector>

#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/image.h"

namespace pixelcloth::viz {

/// Joint-angle histograms as in the paper's pose-sampling figure: one panel per joint and Euler angle (x twist, z,
/// y; degrees over the joint's limits), the poses `before` filtering as grey bars and those kept `after` it as
/// blue bars on top, each normalised to its own count so the shapes compare. Titles name joint and axis; the legend
/// gives both counts.
core::RgbImage renderJointHistograms(const std::vector<body::Pose>& before, const std::vector<body::Pose>& after,
                                     int bins = 18);

}  // namespace pixelcloth::viz
