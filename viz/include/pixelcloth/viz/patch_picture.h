#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "pixelcloth/core/image.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/patch.h"

namespace pixelcloth::viz {

/// A curve to draw over the patches: a chain of garment vertices and its kind (a cage curve's, or a garment's seam or
/// pattern line).
struct PictureCurve {
  std::vector<int> vertices;
  bool closed = false;
  garment::CurveKind kind = garment::CurveKind::Seam;
};

/// Picture of a garment's patches: every layout in its own `size` x `size` cloth-image frame (layoutFrame), side by
/// side in `layouts` order under a title row naming them; each patch tinted with its own colour, the cage curves drawn
/// thick in one colour per kind (seam dark red, loop blue, centre line green, opening black, split orange), and each
/// patch's id written at its area centroid. A curve edge is drawn in every layout that has it as a mesh edge.
core::RgbImage renderPatches(const garment::Garment& garment, const std::vector<patches::Patch>& patches,
                             const std::vector<PictureCurve>& curves, int size = 512);

}  // namespace pixelcloth::viz
