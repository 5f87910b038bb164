#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::sim {

/// Per vertex of garment `b`, the distance (metres) from its position in `xb` to where garment `a` (positions `xa`)
/// lies at the same point of the sewing pattern: `a`'s positions rasterised onto a `size` x `size` cloth image of
/// each layout and sampled bilinearly at `b`'s UVs there (patches::buildRaster / buildSample in `a`'s layout frames),
/// so two meshes of one pattern compare point by point. Garments with the same faces compare vertex by vertex. A
/// vertex of `b` in two layouts (on a side seam) takes the mean of both. Throws InputError when a layout of `b` has no
/// layout of the same name in `a`, or when the positions do not match the garments' vertex counts.
Eigen::VectorXd distancesThroughPattern(const garment::Garment& a, const Eigen::MatrixX3d& xa,
                                        const garment::Garment& b, const Eigen::MatrixX3d& xb, int size = 512);

/// The mean and the largest of per-vertex distances (metres), over the finite ones (distancesThroughPattern leaves
/// NaN where no pixel of the first garment lies near a vertex); 0 and 0 when none is.
struct DistanceSummary {
  double mean = 0, max = 0;
};
DistanceSummary summarise(const Eigen::VectorXd& distances);

/// The samples two datasets hold for the same poses (identical pose vectors), compared through the pattern: how far
/// apart two simulations of one pose end (two meshes of a pattern, two continuation paths).
struct ShapeComparison {
  int rowsA = 0, rowsB = 0;
  std::vector<std::pair<int, int>> rows;  ///< matched samples: (row in a, row in b), in b's row order
  std::vector<double> mean, max;          ///< per matched pair, over b's vertices (metres)
  /// Mean over the matched pairs of their mean distance (metres); 0 without pairs.
  double meanDistance() const;
  /// The largest vertex distance of any pair (metres).
  double maxDistance() const;
};

/// Compares every sample of `b` whose pose vector some sample of `a` also holds (distancesThroughPattern, the
/// datasets' own garments); samples that share a pose pair up in row order. Throws InputError when the datasets'
/// pose sizes differ.
ShapeComparison compareDatasets(const data::Dataset& a, const data::Dataset& b, int size = 512);

}  // namespace pixelcloth::sim
