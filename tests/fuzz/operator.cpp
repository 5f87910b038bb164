// patches::loadRasterOperator / loadSampleOperator: the binary operator files (frame, sparse matrix, mask,
// vertices) behind a 64-bit FNV-1a checksum. Mutated bytes would almost never get past the checksum, so the target
// appends the right one: the input is the file without its last 8 bytes. First byte: even raster, odd sample.
#include "fuzz_support.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/frame.h"
#include "pixelcloth/patches/raster.h"

#include <cstring>
#include <iterator>
#include <string>

namespace {
std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* out = pixelcloth::fuzz::seedOut()) {
    // The 100-vertex necktie's operators at 16 x 16 pixels, as saveOperator writes them, less the checksum and behind
    // the kind byte.
    pixelcloth::garment::NecktieOptions options;
    options.targetVertices = 100;
    const auto tie = pixelcloth::garment::makeNecktie(options);
    const auto frame = pixelcloth::patches::layoutFrame(tie, 0, 16);
    const auto raster = pixelcloth::patches::buildRaster(tie, 0, frame);
    const auto sample = pixelcloth::patches::buildSample(tie, raster);
    const std::filesystem::path folder(out);
    pixelcloth::patches::saveOperator(folder / "raster.tmp-op", raster);
    pixelcloth::patches::saveOperator(folder / "sample.tmp-op", sample);
    for (const char* kind : {"raster", "sample"}) {
      std::ifstream in(folder / (std::string(kind) + ".tmp-op"), std::ios::binary);
      std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      bytes.resize(bytes.size() - 8);
      std::ofstream(folder / (std::string(kind) + "_16.bin"), std::ios::binary)
          << (kind[0] == 'r' ? '\0' : '\1') << bytes;
      std::filesystem::remove(folder / (std::string(kind) + ".tmp-op"));
    }
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::uint64_t checksum = fnv1a(bytes);
  bytes.append(reinterpret_cast<const char*>(&checksum), 8);
  const auto path = pixelcloth::fuzz::writeInput("input.op", reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                                 bytes.size());
  if (data[0] % 2) return pixelcloth::fuzz::guarded([&] { pixelcloth::patches::loadSampleOperator(path); });
  return pixelcloth::fuzz::guarded([&] { pixelcloth::patches::loadRasterOperator(path); });
}
