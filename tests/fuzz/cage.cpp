// cage::cageFromJson on a file read by core::readJson: the cage of a body or garment folder.
#include "fuzz_support.h"
#include "pixelcloth/cage/cage.h"
#include "pixelcloth/core/json_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("cage.json", data, size);
  return pixelcloth::fuzz::guarded(
      [&] { pixelcloth::cage::cageFromJson(pixelcloth::core::readJson(path), path.string()); });
}
