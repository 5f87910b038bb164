#pragma once

// Assembly of the networks' predictions into one garment (DESIGN.md, "Stitching"): the plain per-vertex mean. The
// PCA filter and the GAN blender come next (issue 14).

#include <Eigen/Core>
#include <vector>

#include "pixelcloth/learn/predict.h"

namespace pixelcloth::stitch {

/// Each vertex's values as the mean of every network that predicts it (a whole-garment network alone: its values):
/// batch x 3 * numVertices. Throws InputError naming the first vertex no network covers (a patch folder with patches
/// missing).
Eigen::MatrixXf assembleMean(const std::vector<learn::NetworkPrediction>& predictions, int numVertices);

/// How many networks predict each vertex (#V): 1 inside a patch, 2 or more around the cage curves.
Eigen::VectorXi coverage(const std::vector<learn::NetworkPrediction>& predictions, int numVertices);

}  // namespace pixelcloth::stitch
