// Shared files, CRC-32 and byte comparison: what the dataset writer, merge and check share.
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "dataset_internal.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/data/dataset.h"

namespace pixelcloth::data {

namespace fs = std::filesystem;

namespace detail {

std::vector<std::string> sharedFiles(const fs::path& folder) {
  std::vector<std::string> files = {kRestPositions, "embedding_triangle.npy", "embedding_barycentric.npy",
                                    "embedding_tangent.npy"};
  for (const char* sub : {"body", "garment"}) {
    std::error_code ec;
    if (!fs::is_directory(folder / sub, ec)) continue;
    std::vector<std::string> inside;
    for (const auto& entry : fs::directory_iterator(folder / sub)) {
      const std::string name = entry.path().filename().string();
      if (entry.is_regular_file() && name.find(".tmp-") == std::string::npos)
        inside.push_back(std::string(sub) + "/" + name);
    }
    std::sort(inside.begin(), inside.end());
    files.insert(files.end(), inside.begin(), inside.end());
  }
  return files;
}

std::uint32_t crc32Update(std::uint32_t crc, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const Bytef*>(data);
  while (bytes > 0) {
    const uInt n = static_cast<uInt>(std::min<std::size_t>(bytes, 1u << 30));
    crc = static_cast<std::uint32_t>(::crc32(crc, p, n));
    p += n;
    bytes -= n;
  }
  return crc;
}

CrcWriter::CrcWriter(const fs::path& path) : path_(path), out_(path, std::ios::binary) {
  PIXELCLOTH_CHECK(out_, path.string() << ": cannot open for writing");
}

void CrcWriter::write(const void* data, std::size_t bytes) {
  out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  crc_ = crc32Update(crc_, data, bytes);
  size_ += bytes;
}

std::uint32_t CrcWriter::close() {
  out_.close();
  PIXELCLOTH_CHECK(out_, path_.string() << ": write failed (disk full?)");
  return crc_;
}

void readAt(std::ifstream& in, const fs::path& path, std::int64_t offset, void* data, std::size_t bytes) {
  in.clear();
  in.seekg(offset);
  in.read(static_cast<char*>(data), static_cast<std::streamsize>(bytes));
  PIXELCLOTH_CHECK(in,
                   path.string() << ": cannot read " << bytes << " bytes at offset " << offset << " (truncated file?)");
}

bool sameBytes(const fs::path& a, const fs::path& b) {
  std::error_code ea, eb;
  if (!fs::is_regular_file(a, ea) || !fs::is_regular_file(b, eb)) return false;
  if (fs::file_size(a, ea) != fs::file_size(b, eb)) return false;
  std::ifstream ia(a, std::ios::binary), ib(b, std::ios::binary);
  std::vector<char> ba(1 << 16), bb(1 << 16);
  while (ia && ib) {
    ia.read(ba.data(), ba.size());
    ib.read(bb.data(), bb.size());
    if (ia.gcount() != ib.gcount() || std::memcmp(ba.data(), bb.data(), ia.gcount()) != 0) return false;
  }
  return true;
}

void checkFinite(const float* values, std::int64_t count, const std::string& path, std::int64_t firstElement,
                 std::int64_t rowLength) {
  for (std::int64_t i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) {
      const std::int64_t element = firstElement + i;
      PIXELCLOTH_FAIL(path << ": value " << values[i] << " at row " << element / rowLength + 1 << ", element "
                           << element % rowLength + 1 << " (counting from 1) is not finite");
    }
  }
}

}  // namespace detail

std::uint32_t fileCrc32(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  PIXELCLOTH_CHECK(in, path.string() << ": cannot open for reading");
  std::vector<char> buffer(1 << 20);
  std::uint32_t crc = 0;
  while (in) {
    in.read(buffer.data(), buffer.size());
    crc = detail::crc32Update(crc, buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  PIXELCLOTH_CHECK(in.eof(), path.string() << ": read failed");
  return crc;
}

}  // namespace pixelcloth::data
