// Internals shared by the dataset sources: streamed .npy files (headers, rows, CRC-32 while writing) and file names.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "pixelcloth/data/dataset.h"

namespace pixelcloth::data::detail {

inline constexpr const char* kManifest = "manifest.json";
inline constexpr const char* kPartial = "partial";
inline constexpr const char* kPoses = "poses.npy";
inline constexpr const char* kPositions = "positions.npy";
inline constexpr const char* kOffsets = "offsets.npy";
inline constexpr const char* kSplit = "split.npy";
inline constexpr const char* kRestPositions = "rest_positions.npy";

/// The files every finished dataset holds besides manifest.json, relative to its folder (body/ and garment/ files
/// are listed from the folder itself).
std::vector<std::string> sharedFiles(const std::filesystem::path& folder);

/// False for shared files that legitimately differ between runs that made the same data (garment.json records the
/// meshing time); the others must be byte-identical when a dataset is resumed or shards are merged.
inline bool byteComparable(const std::string& sharedFile) { return sharedFile != "garment/garment.json"; }

/// Appends bytes to a file while computing their CRC-32.
class CrcWriter {
 public:
  explicit CrcWriter(const std::filesystem::path& path);
  void write(const void* data, std::size_t bytes);
  /// Closes and checks the stream; returns the CRC-32 of everything written.
  std::uint32_t close();
  std::uint32_t crc() const { return crc_; }
  std::uint64_t size() const { return size_; }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  std::uint32_t crc_ = 0;
  std::uint64_t size_ = 0;
};

/// CRC-32 of a byte range, continuing from `crc` (zlib's crc32).
std::uint32_t crc32Update(std::uint32_t crc, const void* data, std::size_t bytes);

/// Reads `bytes` at `offset` of an open file; throws `InputError` naming `path` when it cannot.
void readAt(std::ifstream& in, const std::filesystem::path& path, std::int64_t offset, void* data, std::size_t bytes);

/// True when two files have the same bytes.
bool sameBytes(const std::filesystem::path& a, const std::filesystem::path& b);

/// Throws `InputError` naming `path` and the first non-finite value's position (row and element, counted from 1) when
/// a float32 block is not finite.
void checkFinite(const float* values, std::int64_t count, const std::string& path, std::int64_t firstElement,
                 std::int64_t rowLength);

/// A sample of given world positions (imported or rebased, so no solver ran): offsets in the frames of `embedding` on
/// `body` posed with the leading `poseSize` values of `pose` (`context`, a file, prefixes a bad pose's message), and the
/// triangle area ratios as its statistics.
Sample sampleOfPositions(const Eigen::VectorXf& pose, int poseSize, const Eigen::MatrixX3d& positions,
                         const body::Body& body, const garment::Garment& garment, const garment::Embedding& embedding,
                         const std::string& context);

}  // namespace pixelcloth::data::detail
