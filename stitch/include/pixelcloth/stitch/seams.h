#pragma once

// Seam continuity (DESIGN.md, "Metrics"): how far apart the patch networks' predictions of a vertex are before
// blending, how much sharper the garment folds across each cage curve than ground truth does after blending, and the
// error near the curves against the interior. Per cage curve and over all of them.

#include <Eigen/Core>
#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/garment/garment.h"

namespace pixelcloth::stitch {

/// One network's predicted positions of the vertices it covers.
struct PredictedPositions {
  const std::vector<int>* vertices = nullptr;  ///< garment vertices, as in NetworkPrediction
  Eigen::MatrixX3d positions;                  ///< vertices->size() x 3, metres
};

/// The cage curves of a garment as the seam metrics see them (cage::garmentCage), built once.
struct SeamCurve {
  std::string name;
  garment::CurveKind kind = garment::CurveKind::Seam;
  std::vector<int> vertices;  ///< the curve's garment vertices
  /// Per mesh edge of the curve with a triangle on either side: the two faces. Edges on the garment's border (the
  /// openings) have one triangle and no fold angle.
  std::vector<std::array<int, 2>> facePairs;
  std::vector<int> near;  ///< vertices within two rings of the curve (the curve's own included), sorted
};

class SeamLayout {
 public:
  explicit SeamLayout(const garment::Garment& garment);
  const std::vector<SeamCurve>& curves() const { return curves_; }
  /// Vertices within two rings of a curve that patches meet across (every curve but the openings), sorted; and the
  /// rest of the garment.
  const std::vector<int>& nearSeam() const { return nearSeam_; }
  /// Every curve's vertices, each once, sorted; and every curve's two-sided edges (curves share no edge).
  const std::vector<int>& cageVertices() const { return cageVertices_; }
  const std::vector<int>& interior() const { return interior_; }
  const Eigen::MatrixX3i& faces() const { return F_; }
  int numVertices() const { return numVertices_; }

 private:
  std::vector<SeamCurve> curves_;
  std::vector<int> nearSeam_, interior_, cageVertices_;
  Eigen::MatrixX3i F_;
  int numVertices_ = 0;
};

/// Seam metrics accumulated over samples.
class SeamMetrics {
 public:
  explicit SeamMetrics(const SeamLayout& layout);
  /// One sample: `separate` each network's predictions before blending (empty, or one whole-garment prediction: no
  /// gaps to measure), `blended` the garment after assembly and any filter, `truth` ground truth (#V x 3, metres).
  void add(const std::vector<PredictedPositions>& separate, const Eigen::MatrixX3d& blended,
           const Eigen::MatrixX3d& truth);
  /// {"samples", "gap_cm": {"mean", "max"} (null without two predictions of a curve vertex), "normal_jump_deg",
  /// "near_seam_error_cm", "interior_error_cm", "curves": [{"name", "kind", "vertices", "shared_vertices", "gap_cm":
  /// {"mean", "max"}, "normal_jump_deg" (null for a curve with no two-sided edge), "near_seam_error_cm"}]}.
  /// - gap: for each curve vertex two or more networks predict, the largest distance between its predictions.
  /// - normal jump: for each curve edge between two triangles, |fold angle after blending - fold angle in ground
  ///   truth|, the fold angle being the angle between the two triangles' normals; mean over edges and samples.
  /// - errors: mean per-vertex position error near the curves (two rings) and elsewhere.
  nlohmann::json toJson() const;
  int samples() const { return samples_; }

 private:
  struct Sum {
    double gap = 0, gapMax = 0, jump = 0, nearError = 0;
    long long gapCount = 0, jumpCount = 0, nearCount = 0;
  };
  const SeamLayout* layout_;
  std::vector<Sum> curves_;
  Sum all_;
  double interiorError_ = 0;
  long long interiorCount_ = 0;
  std::vector<int> shared_;  ///< per curve: vertices predicted by two or more networks (in the last sample)
  int samples_ = 0;
};

/// The seam gap of one garment: the mean, over the cage-curve vertices that two or more of `separate` predict, of the
/// largest distance between their predictions, cm. NaN when no curve vertex is predicted twice (a whole-garment model).
double meanSeamGapCm(const SeamLayout& layout, const std::vector<PredictedPositions>& separate);

/// The fold angle (degrees) between two triangles' unit normals, rows `pair` of `faceNormals` (core::faceNormals).
double foldAngleDeg(const Eigen::MatrixX3d& faceNormals, const std::array<int, 2>& pair);

}  // namespace pixelcloth::stitch
