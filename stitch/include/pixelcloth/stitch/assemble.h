#pragma once

// Assembly of the networks' predictions into one garment (DESIGN.md, "Stitching"): the plain per-vertex mean, or
// weights feathered by the distance from each patch's own region. The PCA filter (pca_filter.h) and the GAN blender
// (gan.h) work on the assembled garment.

#include <Eigen/Core>
#include <vector>

#include "pixelcloth/garment/garment.h"
#include "pixelcloth/learn/predict.h"

namespace pixelcloth::stitch {

/// Each vertex's values as the mean of every network that predicts it (a whole-garment network alone: its values):
/// batch x 3 * numVertices. Throws InputError naming the first vertex no network covers (a patch folder with patches
/// missing).
Eigen::MatrixXf assembleMean(const std::vector<learn::NetworkPrediction>& predictions, int numVertices);

/// How many networks predict each vertex (#V): 1 inside a patch, 2 or more around the cage curves.
Eigen::VectorXi coverage(const std::vector<learn::NetworkPrediction>& predictions, int numVertices);

/// Feathered assembly of one garment's patch predictions, its weights built once per garment and set of predictions.
/// A patch decoder predicts its patch's own vertices and the ring of neighbouring vertices its enlarged crop holds. A
/// prediction's weight at a vertex is 1 on its own patch and falls smoothly (smoothstep) to 0 at the edge of its crop,
/// by the distance from its own patch along the rest garment's mesh edges: across a cage curve, the neighbour's
/// prediction takes over gradually instead of at the mean's two-rings-wide step. A whole-garment prediction (patch
/// -1) has weight 1 everywhere.
class FeatherAssembler {
 public:
  explicit FeatherAssembler(const garment::Garment& garment);
  /// Batch x 3 * #V, like assembleMean. Throws InputError for a patch id the garment does not have, a vertex no
  /// network covers, or a prediction of the wrong shape.
  Eigen::MatrixXf assemble(const std::vector<learn::NetworkPrediction>& predictions) const;
  /// The weight of `prediction` at each vertex it covers (its vertices' order).
  Eigen::VectorXf weights(const learn::NetworkPrediction& prediction) const;

 private:
  int numVertices_ = 0;
  std::vector<std::vector<int>> ownVertices_;                 ///< per patch id, sorted
  std::vector<std::vector<std::pair<int, double>>> neighbours_;  ///< per vertex: (vertex, rest edge length)
};

}  // namespace pixelcloth::stitch
