#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/cage/cage.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::cage {

/// Settings of dressing (DESIGN.md "Dressing"; paper appendix, "dressing").
struct DressingOptions {
  double clearance = 0.003;      ///< cloth sits this far outside the body surface (metres)
  int maxRelaxIterations = 400;  ///< edge-length equalisation sweeps at most
  double relaxTolerance = 2e-5;  ///< stop when no vertex moves more than this in a sweep (metres)
  /// How a relaxation sweep reaches its per-edge target lengths, (alpha_a + alpha_b) / 2 times the rest length.
  /// false (default): all at once, the least-squares positions whose edge vectors best match targets pointing along
  /// the pattern edge turned into the body's tangent plane by each face's best-fit rotation (one solve with a
  /// Laplacian factorised once per dressing); the rotation keeps every face's orientation, so compressed regions do
  /// not crumple. true: the appendix's literal Jacobi step, each edge corrected along its current direction, half to
  /// each end, averaged per vertex; it takes about a thousand sweeps and flips faces where the cloth is compressed.
  bool jacobiRelaxation = false;
  void validate() const;
};

/// A garment dressed on a body in its rest pose.
struct Dressing {
  Eigen::MatrixX3d morphed;      ///< #V x 3: cage morphed onto the body cage, carried inside by a Poisson solve
  Eigen::MatrixX3d pushed;       ///< #V x 3: `morphed` with vertices inside the body moved out to the surface
  Eigen::MatrixX3d relaxed;      ///< #V x 3: after edge-length equalisation on the body: the dressed garment
  garment::Embedding embedding;  ///< every cloth vertex of `relaxed`, embedded in a body triangle
  /// #V: index into Body::parts of the part each cloth vertex collides with: among the parts that hold its embedding
  /// triangle, the arm part of the sleeve's side for a vertex of a sleeve panel ("left_sleeve_*" -> "left_arm"),
  /// else "torso"; the first part holding the triangle when neither applies.
  std::vector<int> part;
  Eigen::VectorXd areaRatioBefore;  ///< #F: 3D area of `pushed` over pattern area
  Eigen::VectorXd areaRatioAfter;   ///< #F: 3D area of `relaxed` over pattern area
  std::vector<int> cageVertices;    ///< garment vertices placed on the body cage by the morph (held fixed), sorted
  int pushedVertices = 0;           ///< vertices of `morphed` that were inside the body
  double maxPenetration = 0;        ///< deepest vertex of `morphed` inside the body (metres; 0 when none)
  int relaxIterations = 0;
  double relaxResidual = 0;  ///< largest vertex move of the last sweep (metres)
  bool relaxConverged = true;  ///< false when the sweeps stopped at DressingOptions::maxRelaxIterations, still moving
  /// 5th percentile of `areaRatioAfter`: how compressed the most compressed twentieth of the cloth is on the body
  /// (0.62 for the default T-shirt on the mannequin; below kCompressedAreaRatio the garment is too large for the body
  /// and its cage, morphed onto the body's, crumples it).
  double compressedAreaRatio() const;
  /// 95th percentile of `areaRatioAfter`: how stretched the most stretched twentieth is (1.33 for the default T-shirt
  /// on the mannequin; above kStretchedAreaRatio the garment is too small for the body).
  double stretchedAreaRatio() const;
  /// One line, e.g. "412 cage vertices, 37 pushed out (max 1.2 cm deep), 180 sweeps (residual 1.9e-05 m), log2 area
  /// ratio 5-95% [-0.61, 0.40] -> [-0.22, 0.18]".
  std::string summary() const;
};

/// A dressing whose compressedAreaRatio() is below this holds a garment too large for the body; one whose
/// stretchedAreaRatio() is above kStretchedAreaRatio, a garment too small. Graded T-shirts on the mannequin: grade
/// 1.15 gives 0.47 / 1.01, 1.35 gives 0.34 / 0.73, 0.75 gives 1.11 / 2.31 (areas go with the inverse square of the
/// grade).
inline constexpr double kCompressedAreaRatio = 0.5;
inline constexpr double kStretchedAreaRatio = 2.0;
/// What the default T-shirt reaches on the mannequin it was sized for (5th and 95th percentiles).
inline constexpr double kFittingCompressedRatio = 0.62;
inline constexpr double kFittingStretchedRatio = 1.33;

/// The factor to grade the garment by so that its cloth is as compressed and stretched as a fitting garment's: below
/// 1 for a garment too large (sqrt(compressedAreaRatio() / kFittingCompressedRatio)), above 1 for one too small
/// (sqrt(stretchedAreaRatio() / kFittingStretchedRatio)), 1 when it fits (both ratios within their bounds).
double suggestedGrade(const Dressing& dressing);

/// Empty when the garment fits; otherwise one sentence for the user naming the ratio and the size to try, e.g. "the
/// garment is too large for this body: a twentieth of its cloth is compressed to less than 0.34 of its pattern area
/// (a fitting garment keeps about 0.62, below 0.5 it crumples on the body); grade it by about 0.74: for the T-shirt
/// template, `pixelcloth garment tshirt --grade 0.74 --out DIR` (nearest size XS, `--size XS`); for an imported
/// garment, a smaller size of it".
std::string fitAdvice(const Dressing& dressing);

/// Dresses `garment` on `body` (rest T-pose). Cage curves of `garmentCage` that have a namesake in `bodyCage` are
/// morphed onto it by arc length between the junctions they share; curves without one (the shirt's side-panel lines)
/// and all interior vertices follow through a Poisson solve on the garment mesh; then push-out, relaxation and
/// embedding. A garment none of whose curves have a body counterpart (the necktie) keeps its rest placement, pushed
/// out of the body. Throws InputError when the cages do not fit the meshes or the result is not finite.
Dressing dressGarment(const body::Body& body, const Cage& bodyCage, const garment::Garment& garment,
                      const Cage& garmentCage, const DressingOptions& options = {});

/// The pattern's u axis carried onto the 3D surface `positions` (#V x 3), per vertex (#V x 3, not normalised): per face
/// the first column of the deformation gradient F = [x1 - x0, x2 - x0] [uv1 - uv0, uv2 - uv0]^-1, averaged with
/// pattern-area weights over the vertex's faces in its first layout only (the lowest l with vertexUV(v, l) >= 0): the
/// back layout's u axis may point the opposite way in 3D, so averaging across a side seam would cancel. The
/// u-directions to embed a dressed garment with (garment::embedClosest). Throws InputError when sizes disagree.
Eigen::MatrixX3d patternUDirections(const garment::Garment& garment, const Eigen::MatrixX3d& positions);

}  // namespace pixelcloth::cage
