// data::readDatasetInfo: a dataset folder's manifest.json (settings, counts, stats, checksums).
#include "fuzz_support.h"
#include "pixelcloth/data/dataset.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("dataset/manifest.json", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::data::readDatasetInfo(path.parent_path()).summary(); });
}
