// Streamed .npy headers and rows, CRC-32, byte comparison: what the dataset writer, merge and check share.
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <regex>

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

std::int64_t NpyHeader::elements() const {
  std::int64_t n = 1;
  for (std::int64_t d : shape) n *= d;
  return n;
}

std::string NpyHeader::shapeString() const { return detail::shapeString(shape); }

std::string shapeString(const std::vector<std::int64_t>& shape) {
  std::string text = "(";
  for (size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + (shape.size() == 1 ? ",)" : ")");
}

NpyHeader readNpyHeader(const fs::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_regular_file(path, ec), file << ": no such file");
  const std::int64_t fileSize = static_cast<std::int64_t>(fs::file_size(path, ec));
  std::ifstream in(path, std::ios::binary);
  PIXELCLOTH_CHECK(in && !ec, file << ": cannot open for reading");
  unsigned char pre[12] = {};
  in.read(reinterpret_cast<char*>(pre), 10);
  PIXELCLOTH_CHECK(in && std::memcmp(pre, "\x93NUMPY", 6) == 0, file << ": not a NumPy .npy file (bad magic)");
  const int major = pre[6];
  PIXELCLOTH_CHECK(major >= 1 && major <= 3, file << ": unsupported .npy format version " << major);
  std::int64_t headerLength = pre[8] | (pre[9] << 8);
  std::int64_t preamble = 10;
  if (major > 1) {
    in.read(reinterpret_cast<char*>(pre + 10), 2);
    headerLength |= (std::int64_t(pre[10]) << 16) | (std::int64_t(pre[11]) << 24);
    preamble = 12;
  }
  PIXELCLOTH_CHECK(in && preamble + headerLength <= fileSize, file << ": truncated .npy header");
  std::string header(static_cast<size_t>(headerLength), '\0');
  in.read(header.data(), headerLength);
  PIXELCLOTH_CHECK(in, file << ": cannot read the .npy header");

  NpyHeader result;
  std::smatch m;
  PIXELCLOTH_CHECK(std::regex_search(header, m, std::regex("'descr'\\s*:\\s*'([^']*)'")),
                   file << ": the .npy header has no 'descr'");
  result.dtype = m[1];
  PIXELCLOTH_CHECK(std::regex_search(header, m, std::regex("'fortran_order'\\s*:\\s*(True|False)")) && m[1] == "False",
                   file << ": the .npy header must say 'fortran_order': False");
  PIXELCLOTH_CHECK(std::regex_search(header, m, std::regex("'shape'\\s*:\\s*\\(([^)]*)\\)")),
                   file << ": the .npy header has no 'shape'");
  const std::string dims = m[1];
  const std::regex number("\\d+");
  for (std::sregex_iterator it(dims.begin(), dims.end(), number), end; it != end; ++it)
    result.shape.push_back(std::stoll(it->str()));
  const std::map<std::string, int> sizes = {{"<f4", 4}, {"<f8", 8}, {"<i4", 4}, {"<i8", 8}, {"|u1", 1}};
  auto size = sizes.find(result.dtype);
  PIXELCLOTH_CHECK(size != sizes.end(), file << ": unsupported dtype " << result.dtype);
  result.itemSize = size->second;
  result.dataOffset = preamble + headerLength;
  const std::int64_t needed = result.elements() * result.itemSize;
  PIXELCLOTH_CHECK(fileSize - result.dataOffset == needed,
                   file << ": shape " << result.shapeString() << " of " << result.dtype << " needs " << needed
                        << " bytes of data, the file has " << fileSize - result.dataOffset);
  return result;
}

std::string npyPreamble(const std::string& dtype, const std::vector<std::int64_t>& shape) {
  std::string header = "{'descr': '" + dtype + "', 'fortran_order': False, 'shape': " + shapeString(shape) + ", }";
  const bool version2 = header.size() + 1 + 10 > 65535;
  const size_t preambleSize = version2 ? 12 : 10;
  header.append((64 - (preambleSize + header.size() + 1) % 64) % 64, ' ');
  header += '\n';
  std::string out("\x93NUMPY", 6);
  out += static_cast<char>(version2 ? 2 : 1);
  out += '\0';
  const std::uint32_t length = static_cast<std::uint32_t>(header.size());
  out += static_cast<char>(length & 0xff);
  out += static_cast<char>((length >> 8) & 0xff);
  if (version2) {
    out += static_cast<char>((length >> 16) & 0xff);
    out += static_cast<char>((length >> 24) & 0xff);
  }
  return out + header;
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
      PIXELCLOTH_FAIL(path << ": value " << values[i] << " at row " << element / rowLength << ", element "
                           << element % rowLength << " is not finite");
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
