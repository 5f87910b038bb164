// Cage lines of an imported garment placed from a body's cage (see body_fit.h; paper section 3).
#include "pixelcloth/patches/body_fit.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/garment/pattern_lines.h"
#include "pixelcloth/patches/frame.h"
#include "pixelcloth/patches/patch.h"

namespace pixelcloth::patches {

namespace {

using garment::CageLine;
using garment::Garment;

/// Where the T-shirt template's neckline centre (the mean of its opening's vertices) sits relative to the mean of the
/// body cage's neckline loop, measured on the built-in mannequin: the garment's neckline lies a little above and in
/// front of the body's, as a worn shirt's does.
const Eigen::Vector3d kNecklineOffset(-0.0019, -0.0055, 0.0286);

/// The dressed positions ride along as a vertex attribute while lines are cut, so that splitEdge interpolates them.
constexpr const char* kDressed = "pixelcloth_fit_dressed";

Eigen::Vector3d dressedOf(const Garment& g, int v) { return g.mesh.vertexAttributes.at(kDressed).row(v).transpose(); }
double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The vertex at a + t (b - a) on the edge (a, b): a itself or b itself within `snap` of them, else a new vertex
/// splitting the edge.
int vertexAtFraction(Garment& g, int a, int b, double t, double snap) {
  if (t <= snap) return a;
  if (t >= 1 - snap) return b;
  return garment::splitEdge(g, a, b, t);
}

/// The vertex where `field` crosses zero on the edge (a, b) (field values fa, fb of opposite signs).
int vertexAtCrossing(Garment& g, int a, int b, double fa, double fb, double snap) {
  return vertexAtFraction(g, a, b, fa == fb ? 0.0 : fa / (fa - fb), snap);
}

bool crosses(double fa, double fb) { return (fa <= 0 && fb > 0) || (fa > 0 && fb <= 0); }

/// A point along an open chain: between chain[i] and chain[i + 1], at fraction t.
struct ChainPoint {
  size_t i = 0;
  double t = 0;
  double position() const { return static_cast<double>(i) + t; }
};

/// The first point of an open chain where `field` (a function of a vertex) crosses zero.
template <typename Field>
std::optional<ChainPoint> chainCrossing(const std::vector<int>& chain, Field field) {
  for (size_t i = 0; i + 1 < chain.size(); ++i) {
    const double fa = field(chain[i]), fb = field(chain[i + 1]);
    if (crosses(fa, fb)) return ChainPoint{i, fa == fb ? 0.0 : fa / (fa - fb)};
  }
  return std::nullopt;
}

/// The vertex at a chain point: an end of its edge within `snap`, else a new vertex splitting the edge.
int vertexAt(Garment& g, const std::vector<int>& chain, const ChainPoint& point, double snap) {
  return vertexAtFraction(g, chain[point.i], chain[point.i + 1], point.t, snap);
}

/// The layout of the face along boundary edge (a, b), or -1.
int faceLayoutOfEdge(const Garment& g, int a, int b) {
  for (int f = 0; f < g.mesh.numFaces(); ++f) {
    int hits = 0;
    for (int k = 0; k < 3; ++k) hits += g.mesh.F(f, k) == a || g.mesh.F(f, k) == b;
    if (hits == 2) return g.faceLayout[f];
  }
  return -1;
}

/// The crossing of `field` along a closed loop (an opening) on an edge of `layout`'s faces nearest `near` (pattern
/// space of that layout), as a vertex.
template <typename Field>
std::optional<int> loopCrossing(Garment& g, const std::vector<int>& loop, int layout, Field field,
                                const Eigen::Vector2d& near, double snap) {
  int bestA = -1, bestB = -1;
  double bestFa = 0, bestFb = 0, bestDistance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < loop.size(); ++i) {
    const int a = loop[i], b = loop[(i + 1) % loop.size()];
    const double fa = field(a), fb = field(b);
    if (!crosses(fa, fb) || faceLayoutOfEdge(g, a, b) != layout) continue;
    const double t = fa == fb ? 0.0 : fa / (fa - fb);
    const double distance = ((1 - t) * g.uvOf(a, layout) + t * g.uvOf(b, layout) - near).norm();
    if (distance < bestDistance) bestDistance = distance, bestA = a, bestB = b, bestFa = fa, bestFb = fb;
  }
  if (bestA < 0) return std::nullopt;
  return vertexAtCrossing(g, bestA, bestB, bestFa, bestFb, snap);
}

/// Layouts faced towards +z on the dressed garment (the front), by their area-weighted dressed normals.
std::vector<bool> frontLayouts(const Garment& g) {
  std::vector<double> z(g.numLayouts(), 0.0);
  for (int f = 0; f < g.mesh.numFaces(); ++f) {
    const Eigen::Vector3d a = dressedOf(g, g.mesh.F(f, 0)), b = dressedOf(g, g.mesh.F(f, 1)),
                          c = dressedOf(g, g.mesh.F(f, 2));
    z[g.faceLayout[f]] += (b - a).cross(c - a).z();
  }
  std::vector<bool> front(g.numLayouts());
  for (int l = 0; l < g.numLayouts(); ++l) front[l] = z[l] > 0;
  return front;
}

/// Layouts holding both vertices.
std::vector<int> layoutsWithBoth(const Garment& g, int a, int b) {
  std::vector<int> layouts;
  for (int l = 0; l < g.numLayouts(); ++l)
    if (g.vertexUV(a, l) >= 0 && g.vertexUV(b, l) >= 0) layouts.push_back(l);
  return layouts;
}

double meanBodyCoordinate(const body::Body& body, const cage::CageCurve& curve, int axis) {
  double sum = 0;
  for (int v : curve.vertices) sum += body.mesh.V(v, axis);
  return sum / static_cast<double>(curve.vertices.size());
}

Eigen::Vector3d loopCentre(const Eigen::MatrixX3d& V, const std::vector<int>& vertices) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int v : vertices) sum += V.row(v).transpose();
  return sum / static_cast<double>(vertices.size());
}

const garment::Opening* findOpening(const Garment& g, const std::string& name) {
  for (const garment::Opening& o : g.openings)
    if (o.name == name) return &o;
  return nullptr;
}

class Fitter {
 public:
  Fitter(Garment& g, const body::Body& body, const cage::Cage& bodyCage, const BodyFitOptions& options,
         BodyFitReport& report)
      : g_(g), body_(body), bodyCage_(bodyCage), options_(options), report_(report), front_(frontLayouts(g)) {}

  /// A closed loop across the two layouts joined by seams `right` and `left` (each crossed where `field` is 0): the
  /// front chain from the right seam to the left, then the back chain walked back. With `fitBandAbove` (the chest),
  /// the crossings are raised where the band between the loop and the top of the layouts would not fit the patch
  /// budget, as the template's chest line sits just below the armpit for that reason (garment.h,
  /// TShirtOptions::chestHeight), but stay 1 cm below the seams' upper ends.
  template <typename Field>
  void seamLoop(const std::string& name, const std::string& right, const std::string& left, Field field,
                bool fitBandAbove = false) {
    const garment::Seam* r = g_.findSeam(right);
    const garment::Seam* l = g_.findSeam(left);
    if (!r || !l) return skip(name, "the garment has no seams " + right + " and " + left);
    std::vector<int> ends;
    for (std::vector<int> chain : {r->vertices, l->vertices}) {
      if (fitBandAbove && dressedOf(g_, chain.back()).y() > dressedOf(g_, chain.front()).y())
        std::reverse(chain.begin(), chain.end());  // from the upper end (the armpit) down
      std::optional<ChainPoint> point = chainCrossing(chain, field);
      if (!point) return skip(name, "the body's " + name + " loop does not cross seams " + right + " and " + left);
      if (fitBandAbove) point = raisedForBand(chain, *point);
      ends.push_back(vertexAt(g_, chain, *point, options_.snap));
    }
    const std::vector<int> layouts = layoutsWithBoth(g_, ends[0], ends[1]);
    if (layouts.size() != 2 || front_[layouts[0]] == front_[layouts[1]])
      return skip(name, "seams " + right + " and " + left + " do not join one front and one back layout");
    const int frontLayout = front_[layouts[0]] ? layouts[0] : layouts[1];
    const int backLayout = front_[layouts[0]] ? layouts[1] : layouts[0];
    std::vector<int> loop = garment::insertPatternLine(g_, frontLayout, ends[0], ends[1], options_.snap);
    const std::vector<int> back = garment::insertPatternLine(g_, backLayout, ends[0], ends[1], options_.snap);
    loop.insert(loop.end(), back.rbegin() + 1, back.rend() - 1);
    add(CageLine{name, garment::CurveKind::Loop, loop, true});
  }

  /// The centre line of the front (or back) layout from the neckline to the hem at the body's centre plane.
  void centreLine(const std::string& name, bool front) {
    const cage::CageCurve* centre = bodyCage_.findCurve(name);
    const garment::Opening* neck = findOpening(g_, "neckline");
    const garment::Opening* hem = findOpening(g_, "hem");
    if (!centre || !neck || !hem) return skip(name, "the garment has no openings neckline and hem");
    const double x = meanBodyCoordinate(body_, *centre, 0);
    auto field = [&](int v) { return dressedOf(g_, v).x() - x; };
    for (int layout = 0; layout < g_.numLayouts(); ++layout) {
      if (front_[layout] != front) continue;
      const std::vector<int> neckLoop = neck->vertices, hemLoop = hem->vertices;
      // Nearest the layout's middle: of a wavy neckline's crossings, the one the centre line runs from.
      const Eigen::Vector2d middle = g_.layoutBounds(layout).center();
      const std::optional<int> top = loopCrossing(g_, neckLoop, layout, field, middle, options_.snap);
      if (!top) continue;
      const std::optional<int> bottom = loopCrossing(g_, hemLoop, layout, field, g_.uvOf(*top, layout), options_.snap);
      if (!bottom) continue;
      add(CageLine{name, garment::CurveKind::CentreLine,
                   garment::insertPatternLine(g_, layout, *top, *bottom, options_.snap), false});
      return;
    }
    skip(name, std::string("no ") + (front ? "front" : "back") + " layout holds both the neckline and the hem");
  }

  /// Side-panel splits from the chest line down to the hem, parallel to the centre line, on both sides of it.
  void sidePanels(bool front) {
    const std::string side = front ? "front" : "back";
    const CageLine* centre = g_.findLine(std::string("centre_") + side);
    const CageLine* chest = g_.findLine("chest");
    const garment::Opening* hem = findOpening(g_, "hem");
    if (!centre || !chest || !hem) return skip("side_panel_" + side, "it needs the chest loop, the centre line and the hem");
    // Copies: adding lines below moves Garment::lines (the openings stay where they are, their chains kept current).
    const std::vector<int> centreChain = centre->vertices;
    std::vector<int> loop = chest->vertices;
    int layout = -1;
    for (int l = 0; l < g_.numLayouts(); ++l)
      if (front_[l] == front && g_.vertexUV(centreChain.front(), l) >= 0 && g_.vertexUV(centreChain.back(), l) >= 0)
        layout = l;
    const int centreVertex = meetingVertex(centreChain, loop);
    if (layout < 0 || centreVertex < 0) return skip("side_panel_" + side, "the centre line does not cross the chest loop");
    const Eigen::Vector2d down =
        (g_.uvOf(centreChain.back(), layout) - g_.uvOf(centreChain.front(), layout)).normalized();
    const double centreX = dressedOf(g_, centreVertex).x();
    // The chest loop's stretch in this layout, from the centre vertex outwards in both directions.
    const auto at = std::find(loop.begin(), loop.end(), centreVertex);
    std::rotate(loop.begin(), at, loop.end());
    for (int direction : {1, -1}) {
      std::vector<int> stretch = {centreVertex};
      for (size_t k = 1; k < loop.size(); ++k) {
        const int v = loop[direction > 0 ? k : loop.size() - k];
        if (g_.vertexUV(v, layout) < 0) break;
        stretch.push_back(v);
      }
      if (stretch.size() < 2) continue;
      double length = 0;
      for (size_t k = 0; k + 1 < stretch.size(); ++k)
        length += (g_.uvOf(stretch[k + 1], layout) - g_.uvOf(stretch[k], layout)).norm();
      const double target = options_.sidePanelFraction * length;
      double walked = 0;
      int start = -1;
      for (size_t k = 0; k + 1 < stretch.size() && start < 0; ++k) {
        const double edge = (g_.uvOf(stretch[k + 1], layout) - g_.uvOf(stretch[k], layout)).norm();
        if (walked + edge >= target) start = vertexAtCrossing(g_, stretch[k], stretch[k + 1], walked - target,
                                                              walked + edge - target, options_.snap);
        walked += edge;
      }
      if (start < 0) continue;
      const Eigen::Vector2d p = g_.uvOf(start, layout);
      auto field = [&](int v) { return cross2(down, g_.uvOf(v, layout) - p); };
      auto fieldOrFar = [&](int v) { return g_.vertexUV(v, layout) >= 0 ? field(v) : 1.0; };
      const std::optional<int> end = loopCrossing(g_, hem->vertices, layout, fieldOrFar, p, options_.snap);
      const std::string hand = dressedOf(g_, start).x() > centreX ? "left" : "right";
      const std::string name = "side_panel_" + side + "_" + hand;
      if (!end) {
        skip(name, "no hem below the chest line");
        continue;
      }
      add(CageLine{name, garment::CurveKind::Split, garment::insertPatternLine(g_, layout, start, *end, options_.snap),
                   false});
    }
  }

  /// Runs `place` (one line's placement); a line that cannot be cut (its straight pattern line leaves the layout) is
  /// skipped with the reason instead of failing the whole fit. The splits it made on the way stay, as extra vertices.
  template <typename Place>
  void attempt(const std::string& name, Place place) {
    try {
      place();
    } catch (const core::InputError& error) {
      skip(name, error.what());
    }
  }

  /// Splits every patch whose box exceeds the pixel budget across its longer side, until all fit.
  void splitLargePatches() {
    for (int round = 0;; ++round) {
      const std::vector<Patch> patches = garmentPatches(g_);
      const Patch* largest = nullptr;
      double largestSide = 0;
      for (const Patch& patch : patches) {
        const double side = patchPixelExtent(g_, patch, options_.imageSize).maxCoeff();
        if (side > largestSide) largestSide = side, largest = &patch;
      }
      report_.patches = static_cast<int>(patches.size());
      report_.largestPatchPixels = largestSide;
      if (largestSide <= options_.patchPixels) return;
      PIXELCLOTH_CHECK(round < 200, g_.name << ": patches still larger than " << options_.patchPixels
                                            << " px after 200 splits");
      splitPatch(*largest);
    }
  }

 private:
  void skip(const std::string& name, const std::string& why) { report_.skipped.push_back(name + ": " + why); }

  void add(CageLine line) {
    report_.lines.push_back(line.name);
    g_.lines.push_back(std::move(line));
  }

  /// `point` on a seam chain running down from its upper end, moved up to where the pattern above it (to the top of
  /// every layout holding the seam, along the seam's direction) fits 97% of the patch budget, if it is lower; never
  /// within 1 cm (of rest length) of the upper end.
  ChainPoint raisedForBand(const std::vector<int>& chain, ChainPoint point) const {
    for (int layout = 0; layout < g_.numLayouts(); ++layout) {
      if (g_.vertexUV(chain.front(), layout) < 0 || g_.vertexUV(chain.back(), layout) < 0) continue;
      const Eigen::Vector2d up = (g_.uvOf(chain.front(), layout) - g_.uvOf(chain.back(), layout)).normalized();
      double top = -std::numeric_limits<double>::infinity();
      for (int v = 0; v < g_.mesh.numVertices(); ++v)
        if (g_.vertexUV(v, layout) >= 0) top = std::max(top, g_.uvOf(v, layout).dot(up));
      const double lowest =
          top - 0.97 * options_.patchPixels * layoutFrame(g_, layout, options_.imageSize).metresPerPixel;
      const std::optional<ChainPoint> budget =
          chainCrossing(chain, [&](int v) { return lowest - g_.uvOf(v, layout).dot(up); });
      if (budget && budget->position() < point.position()) point = *budget;
    }
    std::vector<double> walked(chain.size(), 0.0);
    for (size_t k = 1; k < chain.size(); ++k)
      walked[k] = walked[k - 1] + (g_.mesh.V.row(chain[k]) - g_.mesh.V.row(chain[k - 1])).norm();
    std::map<int, double> along;
    for (size_t k = 0; k < chain.size(); ++k) along[chain[k]] = walked[k];
    const std::optional<ChainPoint> highest = chainCrossing(chain, [&](int v) { return 0.01 - along[v]; });
    if (highest && highest->position() > point.position()) point = *highest;
    return point;
  }

  static int meetingVertex(const std::vector<int>& a, const std::vector<int>& b) {
    for (int v : a)
      if (std::find(b.begin(), b.end(), v) != b.end()) return v;
    return -1;
  }

  void splitPatch(const Patch& patch) {
    const int layout = patch.layout;
    Eigen::AlignedBox2d box;
    for (int v : patch.vertices) box.extend(g_.uvOf(v, layout));
    // Across the longer side through the box's centre: the line's normal is the longer axis.
    const int axis = box.sizes().x() >= box.sizes().y() ? 0 : 1;
    const double cut = box.center()[axis];
    struct Crossing {
      double along;
      int a, b;
      double fa, fb;
    };
    std::vector<Crossing> crossings;
    const std::vector<int>& loop = patch.boundary;
    for (size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      const Eigen::Vector2d pa = g_.uvOf(a, layout), pb = g_.uvOf(b, layout);
      const double fa = pa[axis] - cut, fb = pb[axis] - cut;
      if (!crosses(fa, fb)) continue;
      const double t = fa == fb ? 0.0 : fa / (fa - fb);
      crossings.push_back({((1 - t) * pa + t * pb)[1 - axis], a, b, fa, fb});
    }
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& x, const Crossing& y) { return x.along < y.along; });
    PIXELCLOTH_CHECK(crossings.size() >= 2, g_.name << ": patch " << patch.id << " of layout " << g_.layouts[layout]
                                                    << " cannot be split (its outline crosses its middle once)");
    // Crossings alternate in and out of the patch; the longest inside stretch is cut.
    size_t best = 0;
    for (size_t k = 0; k + 1 < crossings.size(); k += 2)
      if (crossings[k + 1].along - crossings[k].along > crossings[best + 1].along - crossings[best].along) best = k;
    const Crossing first = crossings[best], second = crossings[best + 1];
    const int from = vertexAtCrossing(g_, first.a, first.b, first.fa, first.fb, options_.snap);
    // Two different boundary edges: splitting the first leaves the second standing.
    const int to = vertexAtCrossing(g_, second.a, second.b, second.fa, second.fb, options_.snap);
    PIXELCLOTH_CHECK(from != to, g_.name << ": patch " << patch.id << " of layout " << g_.layouts[layout]
                                         << " is too narrow to split across its middle");
    const std::string name = "split_" + g_.layouts[layout] + "_" + std::to_string(++splits_);
    add(CageLine{name, garment::CurveKind::Split, garment::insertPatternLine(g_, layout, from, to, options_.snap),
                 false});
  }

  Garment& g_;
  const body::Body& body_;
  const cage::Cage& bodyCage_;
  const BodyFitOptions& options_;
  BodyFitReport& report_;
  std::vector<bool> front_;
  int splits_ = 0;
};

}  // namespace

void BodyFitOptions::validate() const {
  PIXELCLOTH_CHECK(std::isfinite(sidePanelFraction) && sidePanelFraction > 0.1 && sidePanelFraction < 0.9,
                   "fit: sidePanelFraction " << sidePanelFraction << ", expected 0.1 to 0.9");
  PIXELCLOTH_CHECK(imageSize >= 64 && imageSize <= 4096, "fit: imageSize " << imageSize << ", expected 64 to 4096");
  PIXELCLOTH_CHECK(patchPixels >= 16 && patchPixels <= imageSize,
                   "fit: patchPixels " << patchPixels << ", expected 16 to the image size " << imageSize);
  PIXELCLOTH_CHECK(std::isfinite(snap) && snap >= 0 && snap < 0.5, "fit: snap " << snap << ", expected 0 to 0.5");
}

std::string BodyFitReport::summary() const {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << "moved by (" << moved.x() << ", " << moved.y() << ", " << moved.z()
      << ") m; " << lines.size() << " cage lines";
  if (!lines.empty()) {
    out << " (";
    for (size_t k = 0; k < lines.size(); ++k) out << (k ? ", " : "") << lines[k];
    out << ")";
  }
  out << ", " << addedVertices << " vertices added, " << flippedEdges << " edges flipped, smallest angle "
      << std::setprecision(1) << smallestAngleDegrees << " deg; " << patches << " patches, the largest "
      << std::setprecision(0) << largestPatchPixels << " px";
  if (!skipped.empty()) {
    out << "; not placed: ";
    for (size_t k = 0; k < skipped.size(); ++k) out << (k ? "; " : "") << skipped[k];
  }
  return out.str();
}

BodyFitReport fitGarmentToBody(Garment& garment, const body::Body& body, const BodyFitOptions& options) {
  options.validate();
  PIXELCLOTH_CHECK(garment.lines.empty(),
                   garment.name << ": already has " << garment.lines.size() << " cage lines (" << garment.lines.front().name
                                << ", ...); fitting to a body places them on a garment imported without any");
  BodyFitReport report;
  const int verticesBefore = garment.mesh.numVertices();
  const cage::Cage bodyCage = cage::bodyCage(body);

  if (const garment::Opening* neck = findOpening(garment, "neckline");
      options.alignNeckline && neck && bodyCage.findCurve("neckline")) {
    const Eigen::Vector3d bodyNeck = loopCentre(body.mesh.V, bodyCage.findCurve("neckline")->vertices);
    report.moved = bodyNeck + kNecklineOffset - loopCentre(garment.mesh.V, neck->vertices);
    garment.mesh.V.rowwise() += report.moved.transpose();
  }

  const cage::Dressing dressing = cage::dressGarment(body, bodyCage, garment, cage::garmentCage(garment));
  garment.mesh.vertexAttributes[kDressed] = dressing.relaxed;
  Fitter fitter(garment, body, bodyCage, options, report);
  for (const char* name : {"chest", "waist"}) {
    const cage::CageCurve* loop = bodyCage.findCurve(name);
    if (!loop) continue;
    const double height = meanBodyCoordinate(body, *loop, 1);
    fitter.attempt(name, [&] {
      fitter.seamLoop(
          name, "side_right", "side_left", [&](int v) { return dressedOf(garment, v).y() - height; },
          std::string(name) == "chest");
    });
  }
  for (const char* hand : {"left", "right"}) {
    const std::string name = std::string("bicep_") + hand;
    const cage::CageCurve* loop = bodyCage.findCurve(name);
    if (!loop) continue;
    const double x = meanBodyCoordinate(body, *loop, 0);
    fitter.attempt(name, [&] {
      fitter.seamLoop(name, std::string("underarm_") + hand, std::string("sleeve_top_") + hand,
                      [&](int v) { return dressedOf(garment, v).x() - x; });
    });
  }
  fitter.attempt("centre_front", [&] { fitter.centreLine("centre_front", true); });
  fitter.attempt("centre_back", [&] { fitter.centreLine("centre_back", false); });
  fitter.attempt("side_panel_front", [&] { fitter.sidePanels(true); });
  fitter.attempt("side_panel_back", [&] { fitter.sidePanels(false); });
  fitter.splitLargePatches();
  report.flippedEdges = garment::flipThinTriangles(garment);
  report.smallestAngleDegrees = garment::smallestPatternAngleDegrees(garment);
  garment.mesh.vertexAttributes.erase(kDressed);
  report.addedVertices = garment.mesh.numVertices() - verticesBefore;
  return report;
}

}  // namespace pixelcloth::patches
