#include "pixelcloth/patches/frame.h"

#include <algorithm>

#include "pixelcloth/core/error.h"

namespace pixelcloth::patches {

ImageFrame layoutFrame(const garment::Garment& garment, int layout, int size, double margin) {
  PIXELCLOTH_CHECK(layout >= 0 && layout < garment.numLayouts(),
                   garment.name << ": layout " << layout << " does not exist (" << garment.numLayouts() << " layouts)");
  PIXELCLOTH_CHECK(size > 0, "image size must be positive, got " << size);
  PIXELCLOTH_CHECK(margin >= 0 && margin < 0.5, "image margin must be in [0, 0.5), got " << margin);
  double extent = 0;
  for (int l = 0; l < garment.numLayouts(); ++l) extent = std::max(extent, garment.layoutBounds(l).sizes().maxCoeff());
  Eigen::AlignedBox2d box = garment.layoutBounds(layout);
  ImageFrame frame;
  frame.width = frame.height = size;
  frame.metresPerPixel = extent / ((1.0 - 2.0 * margin) * size);
  Eigen::Vector2d centre = box.center();
  double half = 0.5 * size * frame.metresPerPixel;
  frame.topLeft = Eigen::Vector2d(centre.x() - half, centre.y() + half);
  return frame;
}

}  // namespace pixelcloth::patches
