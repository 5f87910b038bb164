// The T-shirt template: a flat sewing pattern (front, back, two sleeves split along their top and underarm lines),
// laid out as two T-shaped layouts, meshed and stitched (DESIGN.md, "Garment templates").
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "garment_pattern.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/garment.h"

namespace pixelcloth::core {

namespace {

/// Key points of the right half (x > 0, the wearer's left) of the front layout, y up from the hem.
struct TShirtShape {
  double W, L, Xs, Ys, Ya, Xe, Yb, Xn;
  explicit TShirtShape(const TShirtOptions& o)
      : W(o.halfWidth),
        L(o.length),
        Xs(o.shoulderHalfWidth),
        Ys(o.length - o.shoulderDrop),
        Ya(o.length - o.armpitDepth),
        Xe(o.shoulderHalfWidth + o.sleeveLength),
        Yb(o.length - o.shoulderDrop - o.sleeveHemHeight),
        Xn(o.neckHalfWidth) {}
  /// x of the armhole line (shoulder point to armpit) at height y, for x > 0.
  double armholeX(double y) const { return W + (Xs - W) * (y - Ya) / (Ys - Ya); }
  /// Whether a point (x, y) of the pattern lies in a sleeve (beyond the armhole line).
  bool inSleeve(double x, double y) const { return y > Ya && std::abs(x) > armholeX(y); }
};

/// Quarter-ellipse neckline from the right neck-side point (-Xn, L) through the centre (0, L - depth) to (Xn, L).
pattern::Curve neckline(const std::string& name, double Xn, double L, double depth) {
  constexpr int kPoints = 256;
  pattern::Curve curve{name, {}, false};
  for (int i = 0; i <= kPoints; ++i) {
    double theta = -M_PI / 2 + M_PI * i / kPoints;
    curve.points.emplace_back(Xn * std::sin(theta), L - depth * std::cos(theta));
  }
  curve.points.front() = Eigen::Vector2d(-Xn, L);
  curve.points.back() = Eigen::Vector2d(Xn, L);
  return curve;
}

double smoothstep(double e0, double e1, double x) {
  double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

/// Shoelace area of a closed polygon.
double polygonArea(const std::vector<Eigen::Vector2d>& p) {
  double area = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const auto& a = p[i];
    const auto& b = p[(i + 1) % p.size()];
    area += a.x() * b.y() - a.y() * b.x();
  }
  return std::abs(area) / 2;
}

}  // namespace

void TShirtOptions::validate() const {
  PIXELCLOTH_CHECK(targetVertices >= 100 && targetVertices <= 200000,
                   "T-shirt options: targetVertices must be in [100, 200000], got " << targetVertices);
  auto positive = [](double value, const char* field) {
    PIXELCLOTH_CHECK(std::isfinite(value) && value > 0,
                     "T-shirt options: " << field << " must be a positive length in metres, got " << value);
  };
  positive(length, "length");
  PIXELCLOTH_CHECK(boundarySpacing >= 0.3 && boundarySpacing <= 3,
                   "T-shirt options: boundarySpacing must be in [0.3, 3], got " << boundarySpacing);
  positive(halfWidth, "halfWidth");
  positive(shoulderHalfWidth, "shoulderHalfWidth");
  positive(armpitDepth, "armpitDepth");
  positive(sleeveLength, "sleeveLength");
  positive(sleeveHemHeight, "sleeveHemHeight");
  positive(neckHalfWidth, "neckHalfWidth");
  positive(frontNeckDepth, "frontNeckDepth");
  positive(backNeckDepth, "backNeckDepth");
  positive(neckSideHeight, "neckSideHeight");
  positive(torsoDepth, "torsoDepth");
  positive(sleeveDepth, "sleeveDepth");
  PIXELCLOTH_CHECK(std::isfinite(shoulderDrop) && shoulderDrop >= 0,
                   "T-shirt options: shoulderDrop must be >= 0 metres, got " << shoulderDrop);
  PIXELCLOTH_CHECK(neckHalfWidth < shoulderHalfWidth && shoulderHalfWidth < halfWidth,
                   "T-shirt options: expected neckHalfWidth < shoulderHalfWidth < halfWidth, got "
                       << neckHalfWidth << ", " << shoulderHalfWidth << ", " << halfWidth);
  PIXELCLOTH_CHECK(armpitDepth > shoulderDrop + 0.02 && armpitDepth < length - 0.05,
                   "T-shirt options: armpitDepth must leave an armhole of at least 2 cm below the shoulder drop ("
                       << shoulderDrop << ") and a side seam of at least 5 cm above the hem (length " << length
                       << "), got " << armpitDepth);
  const double armholeHeight = armpitDepth - shoulderDrop;
  // The mesher keeps every angle >= 20.7 degrees only where the pattern has no corner sharper than 60 degrees: the
  // armhole must be steeper than 60 degrees.
  PIXELCLOTH_CHECK(halfWidth - shoulderHalfWidth <= armholeHeight / std::tan(M_PI / 3),
                   "T-shirt options: the armhole (from the shoulder point to the armpit) must be steeper than 60 "
                   "degrees: halfWidth - shoulderHalfWidth = "
                       << halfWidth - shoulderHalfWidth << " must be <= " << armholeHeight / std::tan(M_PI / 3));
  PIXELCLOTH_CHECK(shoulderHalfWidth + sleeveLength > halfWidth + 0.02,
                   "T-shirt options: the sleeve must reach at least 2 cm past the body's side: shoulderHalfWidth + "
                   "sleeveLength = "
                       << shoulderHalfWidth + sleeveLength << ", halfWidth = " << halfWidth);
  PIXELCLOTH_CHECK(sleeveHemHeight <= armholeHeight, "T-shirt options: sleeveHemHeight ("
                                                         << sleeveHemHeight << ") must not exceed the armhole height "
                                                         << armholeHeight << " (armpitDepth - shoulderDrop)");
  PIXELCLOTH_CHECK(frontNeckDepth < armpitDepth && backNeckDepth < armpitDepth,
                   "T-shirt options: neckline depths (" << frontNeckDepth << ", " << backNeckDepth
                                                        << ") must be less than armpitDepth " << armpitDepth);
}

Garment makeTShirt(const TShirtOptions& options) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  const TShirtShape s(options);
  using P = Eigen::Vector2d;
  // Key points of the pattern in garment coordinates; L is the wearer's left (x > 0), R the right. The shoulder point
  // is the top of the armhole, the neck point the neck-side point, sleeveTop / sleeveBottom the ends of the sleeve hem.
  const P hemL(s.W, 0), hemR(-s.W, 0), armpitL(s.W, s.Ya), armpitR(-s.W, s.Ya), shoulderL(s.Xs, s.Ys),
      shoulderR(-s.Xs, s.Ys), neckL(s.Xn, s.L), neckR(-s.Xn, s.L), sleeveTopL(s.Xe, s.Ys), sleeveTopR(-s.Xe, s.Ys),
      sleeveBottomL(s.Xe, s.Yb), sleeveBottomR(-s.Xe, s.Yb);

  // Curves in garment coordinates. Stitched curves run the same way in both layouts: seams start at the armpit, the
  // neck-side point or the shoulder point; armholes run from the shoulder point to the armpit.
  std::vector<pattern::Curve> curves = {
      pattern::straightCurve("side_left", armpitL, hemL, true),
      pattern::straightCurve("side_right", armpitR, hemR, true),
      pattern::straightCurve("underarm_left", armpitL, sleeveBottomL, true),
      pattern::straightCurve("underarm_right", armpitR, sleeveBottomR, true),
      pattern::straightCurve("shoulder_left", neckL, shoulderL, true),
      pattern::straightCurve("shoulder_right", neckR, shoulderR, true),
      pattern::straightCurve("sleeve_top_left", shoulderL, sleeveTopL, true),
      pattern::straightCurve("sleeve_top_right", shoulderR, sleeveTopR, true),
      pattern::straightCurve("armhole_front_left", shoulderL, armpitL, false),
      pattern::straightCurve("armhole_front_right", shoulderR, armpitR, false),
      pattern::straightCurve("armhole_back_left", shoulderL, armpitL, false),
      pattern::straightCurve("armhole_back_right", shoulderR, armpitR, false),
      pattern::straightCurve("hem_front", hemR, hemL, false),
      pattern::straightCurve("hem_back", hemR, hemL, false),
      neckline("neckline_front", s.Xn, s.L, options.frontNeckDepth),
      neckline("neckline_back", s.Xn, s.L, options.backNeckDepth),
      pattern::straightCurve("sleeve_hem_left_front", sleeveBottomL, sleeveTopL, false),
      pattern::straightCurve("sleeve_hem_right_front", sleeveBottomR, sleeveTopR, false),
      pattern::straightCurve("sleeve_hem_left_back", sleeveBottomL, sleeveTopL, false),
      pattern::straightCurve("sleeve_hem_right_back", sleeveBottomR, sleeveTopR, false),
  };
  auto curveIndex = [&](const std::string& name) {
    for (size_t c = 0; c < curves.size(); ++c)
      if (curves[c].name == name) return static_cast<int>(c);
    throw std::logic_error("makeTShirt: no curve " + name);
  };
  std::vector<int> shared;
  for (size_t c = 0; c < curves.size(); ++c)
    if (curves[c].stitched) shared.push_back(static_cast<int>(c));
  std::vector<pattern::Layout> layouts = {{"front", false, shared}, {"back", true, shared}};
  for (const char* side : {"front", "back"}) {
    auto& layout = layouts[std::string(side) == "front" ? 0 : 1];
    for (const char* curve :
         {"armhole_%_left", "armhole_%_right", "hem_%", "neckline_%", "sleeve_hem_left_%", "sleeve_hem_right_%"}) {
      std::string name(curve);
      name.replace(name.find('%'), 1, side);
      layout.curves.push_back(curveIndex(name));
    }
  }

  auto outline = [&](double neckDepth) {
    return std::vector<P>{
        hemR,  hemL,      armpitL,    sleeveBottomL, sleeveTopL, shoulderL, neckL, P(0, s.L - neckDepth),
        neckR, shoulderR, sleeveTopR, sleeveBottomR, armpitR};
  };
  const double area = polygonArea(outline(options.frontNeckDepth)) + polygonArea(outline(options.backNeckDepth));
  pattern::MergedPattern merged =
      pattern::meshPattern(curves, layouts, options.targetVertices, area, options.boundarySpacing);

  Garment garment;
  garment.name = "tshirt";
  garment.layouts = {"front", "back"};
  garment.panels = {
      "front", "back", "left_sleeve_front", "left_sleeve_back", "right_sleeve_front", "right_sleeve_back"};
  garment.mesh.F = merged.F;
  garment.mesh.UV = merged.UV;
  garment.mesh.FUV = merged.FUV;
  garment.faceLayout = merged.faceLayout;
  garment.vertexUV = merged.vertexUV;

  const int numFaces = static_cast<int>(merged.F.rows());
  garment.facePanel.resize(numFaces);
  for (int f = 0; f < numFaces; ++f) {
    Eigen::Vector2d centroid =
        (merged.XY.row(merged.F(f, 0)) + merged.XY.row(merged.F(f, 1)) + merged.XY.row(merged.F(f, 2))) / 3.0;
    const int layout = merged.faceLayout[f];
    int panel = layout;  // front / back body piece
    if (s.inSleeve(centroid.x(), centroid.y())) panel = (centroid.x() > 0 ? 2 : 4) + layout;
    garment.facePanel[f] = panel;
  }

  // Rest placement: the flat layouts pushed forward (front) and backward (back) from the plane of the stitched seams,
  // rounded near the seams with a circular profile of radius equal to the depth, like a pillow.
  const int numVertices = static_cast<int>(merged.XY.rows());
  const double y0 = options.neckSideHeight - options.length;
  garment.mesh.V.resize(numVertices, 3);
  for (int v = 0; v < numVertices; ++v) {
    const Eigen::Vector2d p = merged.XY.row(v);
    double distance = std::numeric_limits<double>::infinity();
    for (int c : shared) {
      const P& a = curves[c].points.front();
      const P& b = curves[c].points.back();
      const P ab = b - a;
      const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      distance = std::min(distance, (p - (a + t * ab)).norm());
    }
    const double beyondArmhole = p.y() > s.Ya ? std::abs(p.x()) - s.armholeX(p.y()) : std::abs(p.x()) - s.W;
    const double depth =
        options.torsoDepth + (options.sleeveDepth - options.torsoDepth) * smoothstep(-0.03, 0.05, beyondArmhole);
    const double r = std::min(1.0, distance / depth);
    const double z = depth * std::sqrt(std::max(0.0, 1 - (1 - r) * (1 - r)));
    const bool front = merged.vertexUV(v, 0) >= 0, back = merged.vertexUV(v, 1) >= 0;
    garment.mesh.V.row(v) = Eigen::RowVector3d(p.x(), p.y() + y0, front && back ? 0.0 : front ? z : -z);
  }

  // Seams: stitched chains from the front layout, armholes from their own layout.
  for (int c : shared) garment.seams.push_back(Seam{curves[c].name, merged.chains[0][c], true});
  for (const char* name : {"armhole_front_left", "armhole_front_right", "armhole_back_left", "armhole_back_right"}) {
    const int c = curveIndex(name);
    const int layout = std::string(name).find("front") != std::string::npos ? 0 : 1;
    garment.seams.push_back(Seam{name, merged.chains[layout][c], false});
  }

  // Openings: the boundary loops, named after the front curve each contains.
  const std::vector<std::pair<std::string, std::string>> openingCurves = {
      {"hem", "hem_front"},
      {"neckline", "neckline_front"},
      {"sleeve_hem_left", "sleeve_hem_left_front"},
      {"sleeve_hem_right", "sleeve_hem_right_front"}};
  std::vector<std::vector<int>> loops = pattern::boundaryLoops(numVertices, merged.F);
  if (loops.size() != openingCurves.size()) {
    throw std::logic_error("makeTShirt: the stitched shirt has " + std::to_string(loops.size()) +
                           " boundary loops, expected 4");
  }
  for (const auto& [openingName, curveName] : openingCurves) {
    const int probe = merged.chains[0][curveIndex(curveName)][1];
    auto loop = std::find_if(loops.begin(), loops.end(), [&](const std::vector<int>& l) {
      return std::find(l.begin(), l.end(), probe) != l.end();
    });
    if (loop == loops.end()) throw std::logic_error("makeTShirt: no boundary loop for " + openingName);
    garment.openings.push_back(Opening{openingName, *loop});
  }

  garment.meshing = merged.stats;
  garment.meshing.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return garment;
}

}  // namespace pixelcloth::core
