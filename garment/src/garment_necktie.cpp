// The necktie template: one narrow blade with a pointed tip, one layout, hanging flat in front of the chest.
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "garment_pattern.h"
#include "garment_traits.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

using namespace core;

void NecktieOptions::validate() const {
  PIXELCLOTH_CHECK(targetVertices >= 100 && targetVertices <= 200000,
                   "necktie options: targetVertices must be in [100, 200000], got " << targetVertices);
  auto positive = [](double value, const char* field) {
    PIXELCLOTH_CHECK(std::isfinite(value) && value > 0,
                     "necktie options: " << field << " must be a positive length in metres, got " << value);
  };
  positive(length, "length");
  PIXELCLOTH_CHECK(boundarySpacing >= 0.3 && boundarySpacing <= 3,
                   "necktie options: boundarySpacing must be in [0.3, 3], got " << boundarySpacing);
  positive(knotWidth, "knotWidth");
  positive(bladeWidth, "bladeWidth");
  positive(tipHeight, "tipHeight");
  positive(topHeight, "topHeight");
  PIXELCLOTH_CHECK(std::isfinite(frontOffset), "necktie options: frontOffset must be finite, got " << frontOffset);
  PIXELCLOTH_CHECK(bladeWidth >= knotWidth, "necktie options: bladeWidth ("
                                                << bladeWidth << ") must be at least knotWidth (" << knotWidth << ")");
  PIXELCLOTH_CHECK(tipHeight < 0.5 * length, "necktie options: tipHeight ("
                                                 << tipHeight << ") must be less than half the length (" << length
                                                 << ")");
  PIXELCLOTH_CHECK(bands >= 1 && bands <= 20, "necktie options: bands must be in [1, 20], got " << bands);
  PIXELCLOTH_CHECK(length / bands > tipHeight, "necktie options: the lowest band line (length / bands = "
                                                   << length / bands << ") must lie above the tip (tipHeight "
                                                   << tipHeight << ")");
  // The mesher keeps every angle >= 20.7 degrees only where the outline has no corner sharper than 60 degrees.
  PIXELCLOTH_CHECK(0.5 * bladeWidth >= tipHeight * std::tan(M_PI / 6),
                   "necktie options: the tip must not be sharper than 60 degrees: bladeWidth / 2 = "
                       << 0.5 * bladeWidth
                       << " must be >= tipHeight * tan(30 deg) = " << tipHeight * std::tan(M_PI / 6));
}

std::vector<int> necktieKnotVertices(const core::Mesh& mesh) {
  std::vector<int> knot;
  if (mesh.numVertices() == 0) return knot;
  const double top = mesh.V.col(1).maxCoeff();
  for (int v = 0; v < mesh.numVertices(); ++v)
    if (mesh.V(v, 1) > top - 0.04) knot.push_back(v);
  return knot;
}

Garment makeNecktie(const NecktieOptions& options) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  using P = Eigen::Vector2d;
  // Pattern coordinates: x across, y up from the tip.
  const P tip(0, 0), wideL(0.5 * options.bladeWidth, options.tipHeight),
      wideR(-0.5 * options.bladeWidth, options.tipHeight), knotL(0.5 * options.knotWidth, options.length),
      knotR(-0.5 * options.knotWidth, options.length);
  // Band lines at heights length * k / bands, from the right edge to the left edge; the edges carry their ends.
  std::vector<P> edgeLeft = {wideL}, edgeRight = {knotR};
  std::vector<pattern::Curve> bandLines;
  for (int k = 1; k < options.bands; ++k) {
    const double y = options.length * k / options.bands;
    const double t = (y - options.tipHeight) / (options.length - options.tipHeight);
    const P left(wideL.x() + t * (knotL.x() - wideL.x()), y), right(-left.x(), y);
    edgeLeft.push_back(left);
    edgeRight.insert(edgeRight.begin() + 1, right);
    bandLines.push_back(pattern::straightCurve("tie_band_" + std::to_string(k), right, left, false));
  }
  edgeLeft.push_back(knotL);
  edgeRight.push_back(wideR);
  std::vector<pattern::Curve> curves = {
      pattern::straightCurve("tip_left", tip, wideL, false),  pattern::polylineCurve("edge_left", edgeLeft, false),
      pattern::straightCurve("knot", knotL, knotR, false),    pattern::polylineCurve("edge_right", edgeRight, false),
      pattern::straightCurve("tip_right", wideR, tip, false),
  };
  curves.insert(curves.end(), bandLines.begin(), bandLines.end());
  std::vector<pattern::Layout> layouts = {{"tie", false, {}}};
  for (size_t c = 0; c < curves.size(); ++c) layouts[0].curves.push_back(static_cast<int>(c));
  const double area = 0.5 * options.bladeWidth * options.tipHeight +
                      0.5 * (options.bladeWidth + options.knotWidth) * (options.length - options.tipHeight);
  pattern::MergedPattern merged =
      pattern::meshPattern(curves, layouts, options.targetVertices, area, options.boundarySpacing);

  Garment garment;
  garment.name = "necktie";
  garment.layouts = {"tie"};
  garment.panels = {"tie"};
  garment.mesh.F = merged.F;
  garment.mesh.UV = merged.UV;
  garment.mesh.FUV = merged.FUV;
  garment.faceLayout = merged.faceLayout;
  garment.facePanel = Eigen::VectorXi::Zero(merged.F.rows());
  garment.vertexUV = merged.vertexUV;
  const int numVertices = static_cast<int>(merged.XY.rows());
  garment.mesh.V.resize(numVertices, 3);
  const double y0 = options.topHeight - options.length;
  for (int v = 0; v < numVertices; ++v) {
    garment.mesh.V.row(v) = Eigen::RowVector3d(merged.XY(v, 0), merged.XY(v, 1) + y0, options.frontOffset);
  }
  std::vector<std::vector<int>> loops = pattern::boundaryLoops(numVertices, merged.F);
  if (loops.size() != 1)
    throw std::logic_error("makeNecktie: the tie has " + std::to_string(loops.size()) + " boundaries");
  garment.openings.push_back(Opening{"outline", loops[0]});
  for (size_t b = 0; b < bandLines.size(); ++b)
    garment.lines.push_back(CageLine{bandLines[b].name, CurveKind::Split, merged.chains[0][5 + b], false});
  garment.traits = templateTraits("necktie");
  garment.traits.pinned = necktieKnotVertices(garment.mesh);
  garment.meshing = merged.stats;
  garment.meshing.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  garment.recipe = recipeOf(options);
  return garment;
}

}  // namespace pixelcloth::garment
