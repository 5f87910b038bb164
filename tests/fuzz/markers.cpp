// cage::readMarkers: a marker file (docs/markers.md).
#include "fuzz_support.h"
#include "pixelcloth/cage/markers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("markers.json", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::cage::readMarkers(path); });
}
