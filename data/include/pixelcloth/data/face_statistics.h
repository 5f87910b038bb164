#pragma once
// The paper's appendix statistics of a dataset, per garment face over its samples: how far each face's area strays
// from its pattern area, and how often it passes through the garment itself.

#include <Eigen/Core>

#include "pixelcloth/data/dataset.h"

namespace pixelcloth::data {

struct FaceStatistics {
  int samples = 0;
  Eigen::VectorXd minAreaRatio;  ///< per face, the smallest 3D area over pattern area of any sample
  Eigen::VectorXd maxAreaRatio;  ///< per face, the largest
  /// Per face, the fraction of samples in which it intersects another face of the garment.
  Eigen::VectorXd selfIntersection;
  int samplesSelfIntersecting = 0;  ///< samples with at least one pair of intersecting faces
};

/// Over every sample of `dataset` (progress on stderr): each face's area ratios against the dataset's garment pattern
/// and its self-intersections (core::selfIntersections).
FaceStatistics faceStatistics(const Dataset& dataset);

}  // namespace pixelcloth::data
