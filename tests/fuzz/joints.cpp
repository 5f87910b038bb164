// body::readJointPositions: the joints file of a body import.
#include "fuzz_support.h"
#include "pixelcloth/body/body.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("joints.json", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::body::readJointPositions(path); });
}
