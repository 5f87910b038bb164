#include "pixelcloth/learn/spaces.h"

#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::learn {

namespace {
const core::EnumNames<OffsetSpace, 3> kSpaces{
    "offset space",
    {{{OffsetSpace::Local, "local"}, {OffsetSpace::Root, "root"}, {OffsetSpace::Positions, "positions"}}}};
}  // namespace

const char* offsetSpaceName(OffsetSpace space) { return kSpaces.name(space); }

OffsetSpace offsetSpaceFromName(const std::string& name, const std::string& context) {
  return kSpaces.fromName(name, context);
}

Eigen::MatrixX3f valuesInSpace(OffsetSpace space, const garment::EmbeddedFrames& frames,
                               const Eigen::MatrixX3d& positions) {
  PIXELCLOTH_CHECK(positions.rows() == frames.origin.rows(),
                   "offsets: " << positions.rows() << " positions for " << frames.origin.rows() << " frames");
  switch (space) {
    case OffsetSpace::Local: return garment::offsetsFromPositions(frames, positions).cast<float>();
    case OffsetSpace::Root: return (positions - frames.origin).cast<float>();
    case OffsetSpace::Positions: return positions.cast<float>();
  }
  PIXELCLOTH_ASSERT(false, "unknown offset space");
  return {};
}

Eigen::MatrixX3d positionsFromValues(OffsetSpace space, const garment::EmbeddedFrames& frames,
                                     const Eigen::MatrixX3f& values) {
  PIXELCLOTH_CHECK(values.rows() == frames.origin.rows(),
                   "offsets: " << values.rows() << " values for " << frames.origin.rows() << " frames");
  switch (space) {
    case OffsetSpace::Local: return garment::positionsFromOffsets(frames, values.cast<double>());
    case OffsetSpace::Root: return frames.origin + values.cast<double>();
    case OffsetSpace::Positions: return values.cast<double>();
  }
  PIXELCLOTH_ASSERT(false, "unknown offset space");
  return {};
}

}  // namespace pixelcloth::learn
