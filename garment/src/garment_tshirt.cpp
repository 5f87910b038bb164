// The T-shirt template: a flat sewing pattern (front, back, two sleeves split along their top and underarm lines),
// laid out as two T-shaped layouts, meshed and stitched (DESIGN.md, "Garment templates").
#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "garment_pattern.h"
#include "garment_traits.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

using namespace core;

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

constexpr int kNecklinePoints = 256;

/// Half-ellipse neckline from the right neck-side point (-Xn, L) through the centre (0, L - depth) to (Xn, L); point
/// kNecklinePoints / 2 is the centre exactly.
pattern::Curve necklineCurve(const std::string& name, double Xn, double L, double depth) {
  constexpr int kPoints = kNecklinePoints;
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

TShirtOptions TShirtOptions::graded(double factor) const {
  PIXELCLOTH_CHECK(std::isfinite(factor) && factor >= 0.6 && factor <= 1.6,
                   "T-shirt options: grade " << factor << ", expected 0.6 to 1.6 (1: the default size M)");
  TShirtOptions g = *this;
  for (double* length : {&g.length, &g.halfWidth, &g.shoulderHalfWidth, &g.shoulderDrop, &g.armpitDepth,
                         &g.sleeveLength, &g.sleeveHemHeight, &g.neckHalfWidth, &g.frontNeckDepth, &g.backNeckDepth,
                         &g.torsoDepth, &g.chestHeight, &g.waistHeight, &g.sidePanelX, &g.sleeveDepth})
    *length *= factor;
  // The chest loop keeps its fixed centimetre below the armpit (validate), which a smaller grade would eat into.
  g.chestHeight = std::min(g.chestHeight, g.length - g.armpitDepth - 0.01);
  return g;
}

namespace {
const std::vector<std::pair<std::string, double>>& sizeGrades() {
  static const std::vector<std::pair<std::string, double>> grades = {
      {"XS", 0.88}, {"S", 0.94}, {"M", 1.0}, {"L", 1.06}, {"XL", 1.12}, {"XXL", 1.18}};
  return grades;
}
}  // namespace

double sizeGrade(const std::string& size) {
  std::string upper = size;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  std::string names;
  for (const auto& [name, grade] : sizeGrades()) {
    if (name == upper) return grade;
    names += (names.empty() ? "" : ", ") + name;
  }
  PIXELCLOTH_FAIL("--size '" << size << "': unknown size; expected one of " << names << " (or --grade F)");
}

std::string nearestSize(double grade) {
  std::string best;
  double distance = std::numeric_limits<double>::infinity();
  for (const auto& [name, g] : sizeGrades())
    if (std::abs(g - grade) < distance) distance = std::abs(g - grade), best = name;
  return best;
}

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
  const double armpitHeight = length - armpitDepth;
  PIXELCLOTH_CHECK(std::isfinite(waistHeight) && std::isfinite(chestHeight) && 0.02 <= waistHeight &&
                       waistHeight + 0.02 <= chestHeight && chestHeight + 0.01 <= armpitHeight,
                   "T-shirt options: expected 0.02 <= waistHeight, waistHeight + 0.02 <= chestHeight and chestHeight "
                   "+ 0.01 <= armpit height above the hem ("
                       << armpitHeight << "), got waistHeight " << waistHeight << ", chestHeight " << chestHeight);
  PIXELCLOTH_CHECK(
      chestHeight + 0.02 <= length - std::max(frontNeckDepth, backNeckDepth),
      "T-shirt options: chestHeight (" << chestHeight << ") must be at least 2 cm below the neckline's lowest point");
  PIXELCLOTH_CHECK(std::isfinite(sidePanelX) && sidePanelX >= 0.02 && sidePanelX <= halfWidth - 0.02,
                   "T-shirt options: sidePanelX must be in [0.02, halfWidth - 0.02] = [0.02, "
                       << halfWidth - 0.02 << "], got " << sidePanelX);
  PIXELCLOTH_CHECK(std::isfinite(bicepFraction) && bicepFraction >= 0.1 && bicepFraction <= 0.9,
                   "T-shirt options: bicepFraction must be in [0.1, 0.9], got " << bicepFraction);
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

  // Cage-line crossings, built once so that every curve through a crossing carries the same point bit for bit. Chest
  // and waist lines run across the torso from side seam to side seam; the side-panel splits run down from the chest
  // line to the hem at x = +-sx; the bicep lines cross each sleeve at the same fraction of its top and underarm seams.
  const double yc = options.chestHeight, yw = options.waistHeight, sx = options.sidePanelX, tb = options.bicepFraction;
  const P chestL(s.W, yc), chestR(-s.W, yc), waistL(s.W, yw), waistR(-s.W, yw);
  const P bicepTopL = shoulderL + tb * (sleeveTopL - shoulderL), bicepTopR(-bicepTopL.x(), bicepTopL.y()),
          bicepLowL = armpitL + tb * (sleeveBottomL - armpitL), bicepLowR(-bicepLowL.x(), bicepLowL.y());
  auto across = [&](const std::string& name, double y) {
    return pattern::polylineCurve(name, {P(-s.W, y), P(-sx, y), P(0, y), P(sx, y), P(s.W, y)}, false);
  };
  auto sidePanel = [&](const std::string& name, double x) {
    return pattern::polylineCurve(name, {P(x, yc), P(x, yw), P(x, 0)}, false);
  };
  auto neckline = [&](const std::string& name, double depth) {
    pattern::Curve curve = necklineCurve(name, s.Xn, s.L, depth);
    curve.joints = {kNecklinePoints / 2};  // the centre line's top, (0, L - depth) exactly
    return curve;
  };

  // Curves in garment coordinates. Stitched curves run the same way in both layouts: seams start at the armpit, the
  // neck-side point or the shoulder point; armholes run from the shoulder point to the armpit.
  std::vector<pattern::Curve> curves = {
      pattern::polylineCurve("side_left", {armpitL, chestL, waistL, hemL}, true),
      pattern::polylineCurve("side_right", {armpitR, chestR, waistR, hemR}, true),
      pattern::polylineCurve("underarm_left", {armpitL, bicepLowL, sleeveBottomL}, true),
      pattern::polylineCurve("underarm_right", {armpitR, bicepLowR, sleeveBottomR}, true),
      pattern::straightCurve("shoulder_left", neckL, shoulderL, true),
      pattern::straightCurve("shoulder_right", neckR, shoulderR, true),
      pattern::polylineCurve("sleeve_top_left", {shoulderL, bicepTopL, sleeveTopL}, true),
      pattern::polylineCurve("sleeve_top_right", {shoulderR, bicepTopR, sleeveTopR}, true),
      pattern::straightCurve("armhole_front_left", shoulderL, armpitL, false),
      pattern::straightCurve("armhole_front_right", shoulderR, armpitR, false),
      pattern::straightCurve("armhole_back_left", shoulderL, armpitL, false),
      pattern::straightCurve("armhole_back_right", shoulderR, armpitR, false),
      pattern::polylineCurve("hem_front", {hemR, P(-sx, 0), P(0, 0), P(sx, 0), hemL}, false),
      pattern::polylineCurve("hem_back", {hemR, P(-sx, 0), P(0, 0), P(sx, 0), hemL}, false),
      neckline("neckline_front", options.frontNeckDepth),
      neckline("neckline_back", options.backNeckDepth),
      pattern::straightCurve("sleeve_hem_left_front", sleeveBottomL, sleeveTopL, false),
      pattern::straightCurve("sleeve_hem_right_front", sleeveBottomR, sleeveTopR, false),
      pattern::straightCurve("sleeve_hem_left_back", sleeveBottomL, sleeveTopL, false),
      pattern::straightCurve("sleeve_hem_right_back", sleeveBottomR, sleeveTopR, false),
      across("chest_front", yc),
      across("chest_back", yc),
      across("waist_front", yw),
      across("waist_back", yw),
      pattern::polylineCurve("centre_front", {P(0, s.L - options.frontNeckDepth), P(0, yc), P(0, yw), P(0, 0)}, false),
      pattern::polylineCurve("centre_back", {P(0, s.L - options.backNeckDepth), P(0, yc), P(0, yw), P(0, 0)}, false),
      sidePanel("side_panel_front_left", sx),
      sidePanel("side_panel_front_right", -sx),
      sidePanel("side_panel_back_left", sx),
      sidePanel("side_panel_back_right", -sx),
      pattern::straightCurve("bicep_left_front", bicepLowL, bicepTopL, false),
      pattern::straightCurve("bicep_right_front", bicepLowR, bicepTopR, false),
      pattern::straightCurve("bicep_left_back", bicepLowL, bicepTopL, false),
      pattern::straightCurve("bicep_right_back", bicepLowR, bicepTopR, false),
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
    for (const char* curve : {"armhole_%_left", "armhole_%_right", "hem_%", "neckline_%", "sleeve_hem_left_%",
                              "sleeve_hem_right_%", "chest_%", "waist_%", "centre_%", "side_panel_%_left",
                              "side_panel_%_right", "bicep_left_%", "bicep_right_%"}) {
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

  // Cage lines: loops join the front chain (wearer's right to left, or underarm to sleeve top) with the back chain
  // walked back; both chains end on the same stitched seam vertices, which the loop visits once.
  auto chain = [&](const std::string& curveName, int layout) { return merged.chains[layout][curveIndex(curveName)]; };
  auto loop = [&](const std::string& name) {
    std::vector<int> front = chain(name + "_front", 0), back = chain(name + "_back", 1);
    if (front.front() != back.front() || front.back() != back.back())
      throw std::logic_error("makeTShirt: the " + name + " lines do not meet on the stitched seams");
    front.insert(front.end(), back.rbegin() + 1, back.rend() - 1);
    return CageLine{name, CurveKind::Loop, front, true};
  };
  for (const char* name : {"chest", "waist", "bicep_left", "bicep_right"}) garment.lines.push_back(loop(name));
  garment.lines.push_back(CageLine{"centre_front", CurveKind::CentreLine, chain("centre_front", 0), false});
  garment.lines.push_back(CageLine{"centre_back", CurveKind::CentreLine, chain("centre_back", 1), false});
  for (const char* side : {"front", "back"}) {
    for (const char* hand : {"left", "right"}) {
      const std::string name = std::string("side_panel_") + side + "_" + hand;
      garment.lines.push_back(CageLine{name, CurveKind::Split, chain(name, side[0] == 'f' ? 0 : 1), false});
    }
  }

  garment.meshing = merged.stats;
  garment.meshing.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  garment.recipe = recipeOf(options);
  return garment;
}

}  // namespace pixelcloth::garment
