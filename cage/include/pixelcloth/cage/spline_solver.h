#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pixelcloth/cage/cage.h"
#include "pixelcloth/cage/geodesic.h"
#include "pixelcloth/cage/length_model.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::cage {

/// How a cage curve is drawn through its markers (DESIGN.md, "Key-point-to-cage spline solver"):
///  - Linear: straight segments between consecutive markers (baseline).
///  - CatmullRom: the Hermite spline whose tangent at each marker is the central difference over rest arc length,
///    (p[k+1] - p[k-1]) / (L[k-1] + L[k]) (a non-uniform Catmull-Rom with the rest lengths as knot spacing; at the ends
///    of an open curve the parabola through the first (last) three markers); no length term (baseline).
///  - Spline: the same Hermite spline with the tangents solved (Ceres, autodiff) so each segment's arc length matches
///    its target: the worn length a LengthModel predicts (CageSplineSolver::setLengthModel), or without one at least
///    its rest length (cloth stretches); with a bending term and a prior towards the Catmull-Rom tangents (DESIGN.md,
///    "Key-point-to-cage spline solver"); starts from CatmullRom.
enum class CurveMethod { Linear, CatmullRom, Spline };

/// "linear", "catmull_rom", "spline".
const char* curveMethodName(CurveMethod method);
CurveMethod curveMethodFromName(const std::string& name, const std::string& context);

/// Settings of the spline solver.
struct SplineOptions {
  CurveMethod method = CurveMethod::Spline;
  RestLengths restLengths = RestLengths::Pattern;
  /// Relative segment-length error that costs as much as a unit residual (SegmentLengthResidual), > 0.
  double lengthTolerance = 0.01;
  /// Cloth may stretch: a segment longer than its rest length costs nothing, only a shorter one
  /// (SegmentLengthResidual::stretch). false: both directions cost (an inextensible curve).
  bool stretch = true;
  /// Weight of the bending term (BendingResidual) against the length term, >= 0.
  double bendingWeight = 0.05;
  /// Weight of the Catmull-Rom tangent prior (TangentPriorResidual) against the length term, >= 0. Without it the
  /// length term bends nearly straight curves out to make up for the 1-2% their cloth gains in small wrinkles (a bulge
  /// grows with the square root of the extra length), which costs more cage accuracy than it wins on curved loops.
  double tangentPrior = 10;
  /// Noise of the markers, metres. 0: the curve passes through the markers exactly; > 0: marker positions are
  /// unknowns too, held near the observations by MarkerFitResidual with this sigma.
  double markerSigma = 0;
  int maxIterations = 50;  ///< Levenberg-Marquardt iterations per curve, >= 1
  /// Throws InputError naming the field that is out of range.
  void validate() const;
};

/// A C1 piecewise-cubic Hermite curve through K markers, parameterised by rest arc length (spline_residuals.h).
struct CurveSpline {
  bool closed = false;
  bool linear = false;                    ///< straight segments (CurveMethod::Linear); tangents unused
  std::vector<Eigen::Vector3d> points;    ///< K marker positions (fitted ones when markerSigma > 0)
  std::vector<Eigen::Vector3d> tangents;  ///< K derivatives with respect to rest arc length
  std::vector<double> restLengths;        ///< rest length of each segment: K - 1 (open) or K (closed), metres

  int numSegments() const { return static_cast<int>(restLengths.size()); }
  /// Point of segment `segment` (from marker k to k + 1, the last of a closed curve back to 0) at t in [0, 1].
  Eigen::Vector3d position(int segment, double t) const;
  /// Arc length of one segment (Gauss-Legendre), and of the whole curve, metres.
  double arcLength(int segment) const;
  double arcLength() const;
  /// The point of a segment at `fraction` in [0, 1] of its arc length (arc length inverted on a 16-step table).
  Eigen::Vector3d atArcFraction(int segment, double fraction) const;
};

/// What one solve did.
struct SplineSummary {
  int curves = 0;
  int iterations = 0;         ///< Levenberg-Marquardt iterations, summed over curves
  double initialCost = 0;     ///< Ceres cost at the Catmull-Rom start, summed
  double finalCost = 0;       ///< after solving, summed
  double maxLengthError = 0;  ///< largest |arc length - rest length| / rest length of any segment
  /// "31 curves, 112 iterations, cost 812 -> 0.9, max segment length error 0.4%".
  std::string summary() const;
};

/// Fits one curve through `markers` (K x 3 rows, metres, in curve order) whose consecutive rest distances are
/// `restLengths` (K - 1 for an open curve, K for a closed one, each > 0), as `options.method` says. Throws InputError
/// for fewer than 2 markers (3 for a closed curve), wrong counts or non-finite input. `summary`, when given, is
/// accumulated into.
CurveSpline fitCurveSpline(const std::vector<Eigen::Vector3d>& markers, const std::vector<double>& restLengths,
                           bool closed, const SplineOptions& options = {}, SplineSummary* summary = nullptr);

/// Positions of all cage vertices of one frame, from its markers.
struct CageFit {
  Eigen::MatrixX3d positions;       ///< #V x 3: rows of cage vertices set, other rows NaN
  std::vector<CurveSpline> curves;  ///< per cage curve, in Cage::curves order
  SplineSummary summary;
};

/// The cage spline solver of one garment: rest arc lengths of every curve and the curve index of every cage vertex
/// precomputed once, then `solve` per frame. Each curve is solved on its own with the junction markers as shared,
/// fixed points (so curves meeting at a junction meet there: C0 across curves, C1 along each). Every cage vertex is
/// placed at its rest arc-length fraction between the two markers around it, along the fitted curve.
///
/// With a LengthModel (setLengthModel), the spline's segments are held to the lengths it predicts from their markers,
/// in both directions, instead of at least their rest lengths.
class CageSplineSolver {
 public:
  /// `restPositions` (#V x 3, e.g. the dressed garment) is used for RestLengths::Polyline and Geodesic and may be
  /// empty for Pattern. Throws InputError for invalid options or sizes.
  CageSplineSolver(const garment::Garment& garment, const Cage& cage, const Eigen::MatrixX3d& restPositions,
                   const SplineOptions& options = {});
  ~CageSplineSolver();
  CageSplineSolver(CageSplineSolver&&) noexcept;

  /// Solves every curve from `markers` (positions required; markers not on a curve's vertices are ignored by it) with
  /// `options().method`, or with `method`. Throws InputError (naming the curve) when an open curve lacks a marker at
  /// one of its ends or a closed curve has fewer than 3.
  CageFit solve(const MarkerSet& markers) const;
  CageFit solve(const MarkerSet& markers, CurveMethod method) const;

  /// Fits a LengthModel on worn garments: each sample (#V x 3 positions, e.g. a dataset's training split) gives every
  /// curve's segments between the markers of `definition`, their chords and smoothed lengths. `markerSpacing` is
  /// recorded in the model (the spacing `definition` was made with). Throws InputError for no samples or wrong sizes.
  LengthModel fitLengthModel(const MarkerSet& definition, const std::vector<Eigen::MatrixX3d>& samples,
                             double markerSpacing, const LengthModelOptions& options = {}) const;
  /// Uses `model` for every later Spline solve (validated against the garment and cage: InputError naming `context`);
  /// std::nullopt goes back to rest lengths.
  void setLengthModel(std::optional<LengthModel> model, const std::string& context = "length model");
  const std::optional<LengthModel>& lengthModel() const;

  /// The cage vertices, sorted (every vertex of every curve).
  const std::vector<int>& cageVertices() const;
  const Cage& cage() const;
  const SplineOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Length of the polyline through `positions` (#V x 3) along `curve` (closing edge included when closed), metres.
double curvePolylineLength(const Eigen::Ref<const Eigen::MatrixX3d>& positions, const CageCurve& curve);

}  // namespace pixelcloth::cage
