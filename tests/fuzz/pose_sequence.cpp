// data::readPoseSequence, the poses of an import: JSON when the first byte is even, CSV when odd (the rest is the
// file); T-shirt poses (90) or necktie poses (36) by the second byte.
#include "fuzz_support.h"
#include "pixelcloth/data/dataset.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const auto path = pixelcloth::fuzz::writeInput(data[0] % 2 ? "poses.csv" : "poses.json", data + 2, size - 2);
  const int poseSize = data[1] % 2 ? 36 : 90;
  return pixelcloth::fuzz::guarded([&] { pixelcloth::data::readPoseSequence(path, poseSize); });
}
