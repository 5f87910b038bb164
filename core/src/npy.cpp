#include "pixelcloth/core/npy.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <type_traits>

#include "pixelcloth/core/atomic_file.h"

// The element bytes are copied as they are: this assumes a little-endian host (x86-64, arm64).

namespace pixelcloth::core {

namespace fs = std::filesystem;

namespace {

const char kNpyMagic[] = "\x93NUMPY";
constexpr size_t kMagicSize = 6;

int itemSizeOf(const std::string& dtype) {
  if (dtype == "<f4" || dtype == "<i4") return 4;
  if (dtype == "<f8" || dtype == "<i8") return 8;
  if (dtype == "|u1") return 1;
  return 0;
}

std::string prefix(const std::string& source) { return source.empty() ? "npy array" : source; }

// A reader for the Python dict literal of a .npy header:
// {'descr': '<f4', 'fortran_order': False, 'shape': (3, 4), }
class HeaderParser {
 public:
  HeaderParser(std::string text, std::string file) : text_(std::move(text)), file_(std::move(file)) {}

  NpyArray parse() {
    NpyArray array;
    bool haveDescr = false, haveOrder = false, haveShape = false, fortran = false;
    expect('{');
    while (!peek('}')) {
      const std::string key = string();
      expect(':');
      if (key == "descr") {
        array.dtype = string();
        haveDescr = true;
      } else if (key == "fortran_order") {
        fortran = boolean();
        haveOrder = true;
      } else if (key == "shape") {
        array.shape = tuple();
        haveShape = true;
      } else {
        fail("unexpected key '" + key + "'");
      }
      if (!peek('}')) expect(',');
    }
    expect('}');
    PIXELCLOTH_CHECK(
        haveDescr && haveOrder && haveShape,
        file_ << ": malformed npy header: expected the keys 'descr', 'fortran_order' and 'shape' in " << text_);
    PIXELCLOTH_CHECK(!fortran, file_ << ": fortran_order is True; expected C order (in numpy, save "
                                        "numpy.ascontiguousarray(a))");
    std::string dtype = array.dtype;
    if (dtype == "<u1" || dtype == ">u1" || dtype == "=u1") array.dtype = "|u1";  // byte order means nothing for bytes
    PIXELCLOTH_CHECK(dtype.empty() || dtype[0] != '>',
                     file_ << ": dtype " << dtype << " is big-endian; expected little-endian (in numpy, save "
                           << "a.astype('<" << dtype.substr(1) << "'))");
    PIXELCLOTH_CHECK(itemSizeOf(array.dtype) > 0,
                     file_ << ": unsupported dtype '" << dtype << "'; expected one of <f4, <f8, <i4, <i8, |u1");
    return array;
  }

 private:
  void skipSpace() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
  }
  bool peek(char c) {
    skipSpace();
    return at_ < text_.size() && text_[at_] == c;
  }
  void expect(char c) {
    if (!peek(c)) fail(std::string("expected '") + c + "'");
    ++at_;
  }
  [[noreturn]] void fail(const std::string& what) {
    PIXELCLOTH_FAIL(file_ << ": malformed npy header at character " << at_ << ": " << what << " in " << text_);
  }
  std::string string() {
    skipSpace();
    if (at_ >= text_.size() || (text_[at_] != '\'' && text_[at_] != '"')) fail("expected a quoted string");
    const char quote = text_[at_++];
    const size_t end = text_.find(quote, at_);
    if (end == std::string::npos) fail("unterminated string");
    std::string value = text_.substr(at_, end - at_);
    at_ = end + 1;
    return value;
  }
  bool boolean() {
    skipSpace();
    if (text_.compare(at_, 4, "True") == 0) {
      at_ += 4;
      return true;
    }
    if (text_.compare(at_, 5, "False") == 0) {
      at_ += 5;
      return false;
    }
    fail("expected True or False");
  }
  std::vector<std::int64_t> tuple() {
    std::vector<std::int64_t> values;
    expect('(');
    while (!peek(')')) {
      skipSpace();
      size_t start = at_;
      while (at_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[at_]))) ++at_;
      if (at_ == start || at_ - start > 15) fail("expected a dimension (a non-negative integer)");
      values.push_back(std::stoll(text_.substr(start, at_ - start)));
      if (!peek(')')) expect(',');
    }
    expect(')');
    return values;
  }

  std::string text_, file_;
  size_t at_ = 0;
};

template <typename Matrix>
void writeMatrix(const fs::path& path, const Matrix& matrix) {
  using Scalar = typename Matrix::Scalar;
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rowMajor = matrix;
  std::vector<Scalar> values(rowMajor.data(), rowMajor.data() + rowMajor.size());
  writeNpy(path, NpyArray::from(values, {matrix.rows(), matrix.cols()}));
}

std::string expectedShape(std::int64_t rows, std::int64_t cols) {
  auto dim = [](std::int64_t n) { return n < 0 ? std::string("any") : std::to_string(n); };
  return "(" + dim(rows) + ", " + dim(cols) + ")";
}

template <typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> readMatrix(const fs::path& path, std::int64_t rowsExpected,
                                                                 std::int64_t colsExpected) {
  const NpyArray array = readNpy(path);
  array.checkDtype(npyDtype<Scalar>());
  PIXELCLOTH_CHECK(
      array.shape.size() == 2 && (rowsExpected < 0 || array.shape[0] == rowsExpected) &&
          (colsExpected < 0 || array.shape[1] == colsExpected),
      path.string() << ": shape " << array.shapeString() << ", expected " << expectedShape(rowsExpected, colsExpected));
  if constexpr (std::is_floating_point_v<Scalar>) {  // no matrix of ours holds NaN or infinity
    const Scalar* values = array.data<Scalar>();
    const std::int64_t count = array.size(), columns = std::max<std::int64_t>(array.shape[1], 1);
    for (std::int64_t i = 0; i < count; ++i)
      PIXELCLOTH_CHECK(std::isfinite(values[i]), path.string() << ": row " << i / columns + 1 << ", column "
                                                               << i % columns + 1 << " (counting from 1) is "
                                                               << values[i] << "; expected finite numbers");
  }
  using RowMajor = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(array.data<Scalar>(), array.shape[0], array.shape[1]);
}

}  // namespace

std::int64_t NpyArray::size() const {
  std::int64_t n = 1;
  for (std::int64_t d : shape) n *= d;
  return n;
}

int NpyArray::itemSize() const {
  const int size = itemSizeOf(dtype);
  PIXELCLOTH_CHECK(size > 0, prefix(source)
                                 << ": unsupported dtype '" << dtype << "'; expected one of <f4, <f8, <i4, <i8, |u1");
  return size;
}

std::string NpyArray::shapeString() const { return npyShapeString(shape); }

void NpyArray::checkDtype(const std::string& expected) const {
  static const char* const kNames[][2] = {
      {"<f4", "float32"}, {"<f8", "float64"}, {"<i4", "int32"}, {"<i8", "int64"}, {"|u1", "uint8"}};
  std::string name;
  for (const auto& entry : kNames) {
    if (expected == entry[0]) name = std::string(entry[1]) + " ";
  }
  PIXELCLOTH_CHECK(dtype == expected, prefix(source) << ": dtype " << dtype << ", expected " << name << expected);
}

std::string npyShapeString(const std::vector<std::int64_t>& shape) {
  std::string text = "(";
  for (size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + (shape.size() == 1 ? ",)" : ")");
}

std::int64_t NpyHeader::elements() const {
  std::int64_t n = 1;
  for (std::int64_t d : shape) n *= d;
  return n;
}

NpyHeader readNpyHeader(const fs::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::exists(path, ec), file << ": no such file");
  PIXELCLOTH_CHECK(fs::is_regular_file(path, ec), file << ": is not a regular file");
  const std::uintmax_t fileSize = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  PIXELCLOTH_CHECK(in && !ec, file << ": cannot open for reading");

  unsigned char preamble[12] = {};
  in.read(reinterpret_cast<char*>(preamble), 8);
  PIXELCLOTH_CHECK(in && std::memcmp(preamble, kNpyMagic, kMagicSize) == 0,
                   file << ": not a NumPy .npy file (bad magic: expected \\x93NUMPY)");
  const int major = preamble[6];
  PIXELCLOTH_CHECK(major >= 1 && major <= 3, file << ": unsupported .npy format version " << major << "."
                                                  << int(preamble[7]) << "; expected 1.0, 2.0 or 3.0");
  std::uint64_t headerLength = 0;
  size_t preambleSize = 10;
  if (major == 1) {
    in.read(reinterpret_cast<char*>(preamble + 8), 2);
    headerLength = preamble[8] | (preamble[9] << 8);
  } else {
    in.read(reinterpret_cast<char*>(preamble + 8), 4);
    headerLength = preamble[8] | (preamble[9] << 8) | (preamble[10] << 16) | (std::uint64_t(preamble[11]) << 24);
    preambleSize = 12;
  }
  PIXELCLOTH_CHECK(in && preambleSize + headerLength <= fileSize, file << ": truncated: the header needs "
                                                                       << preambleSize + headerLength
                                                                       << " bytes, the file has " << fileSize);
  std::string header(headerLength, '\0');
  in.read(header.data(), static_cast<std::streamsize>(headerLength));
  PIXELCLOTH_CHECK(in, file << ": cannot read the npy header");

  NpyArray array = HeaderParser(header, file).parse();
  array.source = file;
  const int item = array.itemSize();
  std::int64_t count = 1;
  for (std::int64_t d : array.shape) {
    PIXELCLOTH_CHECK(d == 0 || count <= std::numeric_limits<std::int64_t>::max() / item / d,
                     file << ": shape " << array.shapeString() << " is too large");
    count *= d;
  }
  const std::uint64_t needed = static_cast<std::uint64_t>(count) * item;
  const std::uint64_t available = fileSize - preambleSize - headerLength;
  PIXELCLOTH_CHECK(available >= needed, file << ": truncated: shape " << array.shapeString() << " of " << array.dtype
                                             << " needs " << needed << " bytes of data, the file has " << available);
  PIXELCLOTH_CHECK(available == needed, file << ": " << available - needed << " bytes after the data that shape "
                                             << array.shapeString() << " of " << array.dtype
                                             << " needs; the file is not a single .npy array");
  NpyHeader result;
  result.dtype = array.dtype;
  result.shape = array.shape;
  result.itemSize = item;
  result.dataOffset = static_cast<std::int64_t>(preambleSize + headerLength);
  return result;
}

NpyArray readNpy(const fs::path& path) {
  const std::string file = path.string();
  const NpyHeader header = readNpyHeader(path);
  NpyArray array{header.dtype, header.shape, {}, file};
  const std::int64_t needed = header.elements() * header.itemSize;
  std::ifstream in(path, std::ios::binary);
  in.seekg(header.dataOffset);
  array.bytes.resize(static_cast<size_t>(needed));
  in.read(reinterpret_cast<char*>(array.bytes.data()), static_cast<std::streamsize>(needed));
  PIXELCLOTH_CHECK(in, file << ": cannot read " << needed << " bytes of data");
  return array;
}

std::string npyPreamble(const std::string& dtype, const std::vector<std::int64_t>& shape) {
  std::string header = "{'descr': '" + dtype + "', 'fortran_order': False, 'shape': " + npyShapeString(shape) + ", }";
  // Pad with spaces and end with a newline so that the data starts on a 64-byte boundary, as numpy does.
  const bool version2 = header.size() + 1 + 10 > 65535;
  const size_t preambleSize = version2 ? 12 : 10;
  header.append((64 - (preambleSize + header.size() + 1) % 64) % 64, ' ');
  header += '\n';
  std::string preamble(kNpyMagic, kMagicSize);
  preamble += static_cast<char>(version2 ? 2 : 1);
  preamble += '\0';
  for (size_t i = 0; i < preambleSize - 8; ++i) preamble += static_cast<char>((header.size() >> (8 * i)) & 0xff);
  return preamble + header;
}

void writeNpy(const fs::path& path, const NpyArray& array) {
  const std::string file = path.string();
  const int item = itemSizeOf(array.dtype);
  PIXELCLOTH_CHECK(item > 0,
                   file << ": unsupported dtype '" << array.dtype << "'; expected one of <f4, <f8, <i4, <i8, |u1");
  for (std::int64_t d : array.shape) {
    PIXELCLOTH_CHECK(d >= 0, file << ": negative dimension in shape " << array.shapeString());
  }
  PIXELCLOTH_CHECK(static_cast<std::uint64_t>(array.size()) * item == array.bytes.size(),
                   file << ": shape " << array.shapeString() << " of " << array.dtype << " needs "
                        << array.size() * item << " bytes, the array has " << array.bytes.size());
  const std::string preamble = npyPreamble(array.dtype, array.shape);

  writeAtomically(path, [&](const fs::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    PIXELCLOTH_CHECK(out, file << ": cannot open for writing");
    out.write(preamble.data(), static_cast<std::streamsize>(preamble.size()));
    out.write(reinterpret_cast<const char*>(array.bytes.data()), static_cast<std::streamsize>(array.bytes.size()));
    out.close();
    PIXELCLOTH_CHECK(out, file << ": write failed (disk full?)");
  });
}

void writeNpy(const fs::path& path, const Eigen::MatrixXf& matrix) { writeMatrix(path, matrix); }
void writeNpy(const fs::path& path, const Eigen::MatrixXd& matrix) { writeMatrix(path, matrix); }
void writeNpy(const fs::path& path, const Eigen::MatrixXi& matrix) { writeMatrix(path, matrix); }

Eigen::MatrixXf readNpyMatrixF(const fs::path& path, std::int64_t rowsExpected, std::int64_t colsExpected) {
  return readMatrix<float>(path, rowsExpected, colsExpected);
}
Eigen::MatrixXd readNpyMatrixD(const fs::path& path, std::int64_t rowsExpected, std::int64_t colsExpected) {
  return readMatrix<double>(path, rowsExpected, colsExpected);
}
Eigen::MatrixXi readNpyMatrixI(const fs::path& path, std::int64_t rowsExpected, std::int64_t colsExpected) {
  return readMatrix<std::int32_t>(path, rowsExpected, colsExpected);
}

}  // namespace pixelcloth::core
