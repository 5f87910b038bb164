#include "pixelcloth/core/tensor_file.h"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <set>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"

// Integers are copied as they are: this assumes a little-endian host (x86-64, arm64), as the NPY code does.

namespace pixelcloth::core {

namespace fs = std::filesystem;

namespace {

const char kTensorFileMagic[8] = {'P', 'X', 'T', 'E', 'N', 'S', 'O', 'R'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kPreamble = 24;
constexpr std::uint64_t kAlignment = 64;
const char kFormat[] = "pixelcloth.tensors";

// A fuzzing build (scripts/run fuzz) computes the CRC-32s but does not compare them, so that mutated inputs reach the
// JSON header's parser and the array checks behind them: libFuzzer cannot make a checksum match. Every other check
// stays; every other build compares.
#ifdef PIXELCLOTH_FUZZING_BUILD
constexpr bool kCompareCrcs = false;
#else
constexpr bool kCompareCrcs = true;
#endif

std::uint32_t crc32Of(const void* bytes, std::size_t size) {
  std::uint32_t crc = static_cast<std::uint32_t>(::crc32(0L, Z_NULL, 0));
  const auto* p = static_cast<const Bytef*>(bytes);
  while (size > 0) {  // zlib takes a uInt length
    const uInt n = static_cast<uInt>(std::min<std::size_t>(size, 1u << 30));
    crc = static_cast<std::uint32_t>(::crc32(crc, p, n));
    p += n;
    size -= n;
  }
  return crc;
}

std::uint64_t alignUp(std::uint64_t n) { return (n + kAlignment - 1) / kAlignment * kAlignment; }

std::uint32_t readU32(const std::string& bytes, std::size_t at) {
  std::uint32_t value;
  std::memcpy(&value, bytes.data() + at, sizeof value);
  return value;
}

void appendU32(std::string& out, std::uint32_t value) { out.append(reinterpret_cast<const char*>(&value), sizeof value); }

// One entry of "arrays", checked against the file it came from: every field present and of its type, the dtype one
// NpyArray knows, the shape's element count exactly the length, and the bytes inside the file after the header.
NpyArray readArray(const nlohmann::json& entry, const std::string& bytes, std::uint64_t dataStart,
                   const std::string& context) {
  PIXELCLOTH_CHECK(entry.is_object(), context << ": is " << entry.type_name() << ", expected an object");
  NpyArray array;
  array.source = context;
  array.dtype = requireValue<std::string>(entry, "dtype", context);
  const std::int64_t itemSize = array.itemSize();  // refuses an unknown dtype, naming it
  const nlohmann::json& shape = requireField(entry, "shape", context);
  PIXELCLOTH_CHECK(shape.is_array() && shape.size() <= 8,
                   context << ": shape " << shape.dump() << ", expected an array of at most 8 sizes");
  const auto length = requireValue<std::uint64_t>(entry, "bytes", context);
  std::uint64_t elements = 1;
  for (std::size_t d = 0; d < shape.size(); ++d) {
    PIXELCLOTH_CHECK(shape[d].is_number_unsigned() || (shape[d].is_number_integer() && shape[d].get<std::int64_t>() >= 0),
                     context << ": shape " << shape.dump() << ", expected sizes of 0 or more");
    const std::uint64_t size = shape[d].get<std::uint64_t>();
    // Stop before the product can overflow: no shape of ours exceeds the file's length.
    PIXELCLOTH_CHECK(size == 0 || elements <= length / size,
                     context << ": shape " << shape.dump() << " needs more than the " << length << " bytes given");
    elements *= size;
    array.shape.push_back(static_cast<std::int64_t>(size));
  }
  PIXELCLOTH_CHECK(elements <= length / static_cast<std::uint64_t>(itemSize) &&
                       elements * static_cast<std::uint64_t>(itemSize) == length,
                   context << ": " << length << " bytes for shape " << array.shapeString() << " of " << array.dtype
                           << ", which needs " << elements * static_cast<std::uint64_t>(itemSize));
  const auto offset = requireValue<std::uint64_t>(entry, "offset", context);
  PIXELCLOTH_CHECK(offset >= dataStart && offset <= bytes.size() && length <= bytes.size() - offset,
                   context << ": " << length << " bytes at offset " << offset << " are outside the data (bytes "
                           << dataStart << " to " << bytes.size() << "): the file is truncated or damaged");
  const auto crc = requireValue<std::uint32_t>(entry, "crc32", context);
  const std::uint32_t actual = crc32Of(bytes.data() + offset, length);
  PIXELCLOTH_CHECK(!kCompareCrcs || actual == crc, context << ": CRC-32 " << actual << ", the header says " << crc
                                          << ": the file is damaged");
  array.bytes.assign(bytes.begin() + static_cast<std::ptrdiff_t>(offset),
                     bytes.begin() + static_cast<std::ptrdiff_t>(offset + length));
  return array;
}

}  // namespace

const NpyArray* TensorFile::find(const std::string& name) const {
  for (const auto& [key, array] : arrays)
    if (key == name) return &array;
  return nullptr;
}

void writeTensorFile(const fs::path& path, const TensorFile& file) {
  nlohmann::json entries = nlohmann::json::array();
  std::set<std::string> names;
  // The offsets depend on the header's length, which depends on the offsets' digits: lay the data out after a
  // header length guessed from the entries, and grow the guess until the header fits in it.
  std::uint64_t reserved = 256;
  std::string header;
  for (const auto& [name, array] : file.arrays) {
    PIXELCLOTH_CHECK(!name.empty() && names.insert(name).second,
                     path.string() << ": array name '" << name << "' is empty or repeated");
    PIXELCLOTH_CHECK(static_cast<std::int64_t>(array.bytes.size()) == array.size() * array.itemSize(),
                     path.string() << ": array '" << name << "' holds " << array.bytes.size() << " bytes for shape "
                                   << array.shapeString());
  }
  for (;;) {
    entries = nlohmann::json::array();
    std::uint64_t offset = alignUp(kPreamble + reserved);
    for (const auto& [name, array] : file.arrays) {
      entries.push_back({{"name", name},
                         {"dtype", array.dtype},
                         {"shape", array.shape},
                         {"offset", offset},
                         {"bytes", array.bytes.size()},
                         {"crc32", crc32Of(array.bytes.data(), array.bytes.size())}});
      offset = alignUp(offset + array.bytes.size());
    }
    header = nlohmann::json{{"format", kFormat}, {"version", kVersion}, {"kind", file.kind}, {"meta", file.meta},
                            {"arrays", entries}}
                 .dump();
    if (header.size() <= reserved) break;
    reserved = alignUp(header.size());
  }
  header.resize(reserved, ' ');  // JSON allows trailing white space; the data then starts where the offsets say

  std::string out(kTensorFileMagic, sizeof kTensorFileMagic);
  appendU32(out, kVersion);
  appendU32(out, static_cast<std::uint32_t>(header.size()));
  appendU32(out, crc32Of(header.data(), header.size()));
  appendU32(out, 0);
  out += header;
  for (std::size_t i = 0; i < file.arrays.size(); ++i) {
    out.resize(entries[i]["offset"].get<std::uint64_t>(), '\0');
    const auto& bytes = file.arrays[i].second.bytes;
    out.append(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  }
  writeTextAtomically(path, out);
}

TensorFile readTensorFile(const fs::path& path, const std::string& kind) {
  const std::string name = path.string();
  const std::string bytes = readTextFile(path);
  if (bytes.size() >= 4 && bytes.compare(0, 4, "PK\x03\x04") == 0)
    PIXELCLOTH_FAIL(name << ": a zip file, as LibTorch archives are; pixelcloth's " << kind
                         << " files are pixelcloth tensor files (docs/learning.md), which pixelcloth before 2026-12 "
                            "did not write: train the model again");
  PIXELCLOTH_CHECK(bytes.size() >= kPreamble, name << ": " << bytes.size() << " bytes, truncated (a pixelcloth tensor "
                                                            "file starts with a " << kPreamble << "-byte preamble)");
  PIXELCLOTH_CHECK(bytes.compare(0, sizeof kTensorFileMagic, kTensorFileMagic, sizeof kTensorFileMagic) == 0,
                   name << ": not a pixelcloth tensor file (it does not start with PXTENSOR)");
  const std::uint32_t version = readU32(bytes, 8), headerSize = readU32(bytes, 12), headerCrc = readU32(bytes, 16);
  PIXELCLOTH_CHECK(version == kVersion,
                   name << ": tensor file version " << version << ", this pixelcloth reads version " << kVersion);
  PIXELCLOTH_CHECK(headerSize <= bytes.size() - kPreamble,
                   name << ": its header claims " << headerSize << " bytes, the file has " << bytes.size() - kPreamble
                        << " after the preamble: truncated");
  const std::uint32_t actual = crc32Of(bytes.data() + kPreamble, headerSize);
  PIXELCLOTH_CHECK(!kCompareCrcs || actual == headerCrc,
                   name << ": header CRC-32 " << actual << ", the preamble says " << headerCrc << ": the file is damaged");
  const nlohmann::json header =
      parseJson(std::string(bytes.begin() + kPreamble, bytes.begin() + kPreamble + headerSize), name + ": header");
  PIXELCLOTH_CHECK(header.is_object(), name << ": its header is not a JSON object");
  const std::string format = valueOr<std::string>(header, "format", "", name);
  PIXELCLOTH_CHECK(format == kFormat, name << ": format '" << format << "', expected '" << kFormat << "'");
  TensorFile file;
  file.kind = requireValue<std::string>(header, "kind", name);
  PIXELCLOTH_CHECK(file.kind == kind, name << ": holds " << file.kind << ", expected " << kind);
  if (header.contains("meta")) file.meta = header["meta"];
  PIXELCLOTH_CHECK(file.meta.is_object(), name << ": field 'meta' is " << file.meta.type_name() << ", expected an object");
  const nlohmann::json& arrays = requireField(header, "arrays", name);
  PIXELCLOTH_CHECK(arrays.is_array(), name << ": field 'arrays' is " << arrays.type_name() << ", expected an array");
  std::set<std::string> names;
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    const std::string context = name + ": array " + std::to_string(i + 1);
    const std::string arrayName =
        arrays[i].is_object() ? requireValue<std::string>(arrays[i], "name", context) : std::string();
    PIXELCLOTH_CHECK(arrays[i].is_object() && !arrayName.empty() && names.insert(arrayName).second,
                     context << ": expected an object with a name of its own");
    file.arrays.emplace_back(arrayName, readArray(arrays[i], bytes, kPreamble + headerSize, name + ": " + arrayName));
  }
  return file;
}

}  // namespace pixelcloth::core
