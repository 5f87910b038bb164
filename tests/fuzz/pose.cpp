// body::readPose: a pose file ({"pose": [90 floats]} or {"joints": {...}}).
#include "fuzz_support.h"
#include "pixelcloth/body/pose_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("pose.json", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::body::readPose(path); });
}
