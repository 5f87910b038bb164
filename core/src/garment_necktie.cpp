// The necktie template: one narrow blade with a pointed tip, one layout, hanging flat in front of the chest.
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "garment_pattern.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/garment.h"

namespace pixelcloth::core {

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
  // The mesher keeps every angle >= 20.7 degrees only where the outline has no corner sharper than 60 degrees.
  PIXELCLOTH_CHECK(0.5 * bladeWidth >= tipHeight * std::tan(M_PI / 6),
                   "necktie options: the tip must not be sharper than 60 degrees: bladeWidth / 2 = "
                       << 0.5 * bladeWidth
                       << " must be >= tipHeight * tan(30 deg) = " << tipHeight * std::tan(M_PI / 6));
}

Garment makeNecktie(const NecktieOptions& options) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  using P = Eigen::Vector2d;
  // Pattern coordinates: x across, y up from the tip.
  const P tip(0, 0), wideL(0.5 * options.bladeWidth, options.tipHeight),
      wideR(-0.5 * options.bladeWidth, options.tipHeight), knotL(0.5 * options.knotWidth, options.length),
      knotR(-0.5 * options.knotWidth, options.length);
  std::vector<pattern::Curve> curves = {
      pattern::straightCurve("tip_left", tip, wideL, false),  pattern::straightCurve("edge_left", wideL, knotL, false),
      pattern::straightCurve("knot", knotL, knotR, false),    pattern::straightCurve("edge_right", knotR, wideR, false),
      pattern::straightCurve("tip_right", wideR, tip, false),
  };
  std::vector<pattern::Layout> layouts = {{"tie", false, {0, 1, 2, 3, 4}}};
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
  garment.meshing = merged.stats;
  garment.meshing.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return garment;
}

}  // namespace pixelcloth::core
