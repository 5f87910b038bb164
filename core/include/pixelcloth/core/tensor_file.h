#pragma once

// pixelcloth's tensor file: named arrays and a JSON header in one file, each part with its CRC-32. Model weights and
// training checkpoints are kept in it rather than in LibTorch archives, whose zip and pickle readers crash on damaged
// files (docs/reliability.md, finding 12); this reader checks every byte it is given before anything is allocated.
//
// Layout (little endian):
//   bytes  0-7   magic "PXTENSOR"
//   bytes  8-11  version (1)
//   bytes 12-15  header length H
//   bytes 16-19  CRC-32 of the header
//   bytes 20-23  zero
//   bytes 24...  the header: UTF-8 JSON {"format": "pixelcloth.tensors", "kind": K, "meta": {...},
//                "arrays": [{"name", "dtype" (NumPy's: "<f4"), "shape": [...], "offset", "bytes", "crc32"}]}
//   then each array's bytes (C order) at its offset, every offset a multiple of 64.
// tests/core/tensor_file_test.cpp reads one with numpy alone.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "pixelcloth/core/npy.h"

namespace pixelcloth::core {

struct TensorFile {
  std::string kind;                                       ///< what the file holds, e.g. "weights", "checkpoint"
  nlohmann::json meta = nlohmann::json::object();         ///< anything else the writer keeps beside the arrays
  std::vector<std::pair<std::string, NpyArray>> arrays;  ///< in file order; names unique

  /// The array named `name`, or nullptr.
  const NpyArray* find(const std::string& name) const;
};

/// Writes `file` atomically. Throws `InputError` for a repeated or empty name.
void writeTensorFile(const std::filesystem::path& path, const TensorFile& file);

/// Reads a tensor file of kind `kind`. Throws `InputError` naming the file for a missing or truncated file, another
/// format (a LibTorch archive is named as one), another kind, a header or array whose CRC-32 differs, and an array
/// entry whose dtype, shape, offset or length does not fit the file.
TensorFile readTensorFile(const std::filesystem::path& path, const std::string& kind);

}  // namespace pixelcloth::core
