// garment::importGarment's JSON half (garment.json: layouts, panels, seams, openings, cage lines) against a fixed
// garment.obj: the 100-vertex necktie template, saved by saveGarment at start-up.
#include "fuzz_support.h"
#include "pixelcloth/garment/garment.h"

namespace {
std::filesystem::path folder() { return pixelcloth::fuzz::scratch() / "garment"; }
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  pixelcloth::garment::NecktieOptions options;
  options.targetVertices = 100;
  pixelcloth::garment::saveGarment(folder(), pixelcloth::garment::makeNecktie(options));
  if (const char* out = pixelcloth::fuzz::seedOut())
    std::filesystem::copy_file(folder() / "garment.json", std::filesystem::path(out) / "necktie.json",
                               std::filesystem::copy_options::overwrite_existing);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("garment/input.json", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::garment::importGarment(folder() / "garment.obj", path); });
}
