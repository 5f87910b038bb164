// pixelcloth's tensor file (core/tensor_file.h): a round trip, numpy as an independent reader, and every fault the
// reader names: the preamble, the header, each array entry and each array's bytes.
#include "pixelcloth/core/tensor_file.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>

#include "pixelcloth/core/atomic_file.h"
#include "support/python.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace pt = pixelcloth::testing;
namespace fs = std::filesystem;

namespace {

pc::TensorFile sample() {
  pc::TensorFile file;
  file.kind = "weights";
  file.meta = {{"epoch", 3}, {"note", std::string(200, '.')}};  // room for the edits of EveryFaultIsNamed
  file.arrays.emplace_back("0.weight", pc::NpyArray::from(std::vector<float>{1.5f, -2, 3, 4, 5, 6.25f}, {2, 3}));
  file.arrays.emplace_back("0.bias", pc::NpyArray::from(std::vector<double>{0.1, 0.2}, {2}));
  file.arrays.emplace_back("steps", pc::NpyArray::from(std::vector<std::int64_t>{7}, {}));
  file.arrays.emplace_back("empty", pc::NpyArray::from(std::vector<float>{}, {0, 4}));
  return file;
}

// The header of a file writeTensorFile wrote, and the file with a header of our choosing put back (CRC recomputed
// by writing through the JSON: only the header is replaced; offsets are kept as they were).
nlohmann::json headerOf(const std::string& bytes) {
  std::uint32_t size;
  std::memcpy(&size, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(24, size));
}

std::string withHeader(const std::string& bytes, const nlohmann::json& header);

}  // namespace

TEST(TensorFile, RoundTripKeepsNamesOrderDtypesShapesAndMeta) {
  const fs::path dir = pt::freshDir("round");
  pc::writeTensorFile(dir / "a.tensors", sample());
  const pc::TensorFile back = pc::readTensorFile(dir / "a.tensors", "weights");
  const pc::TensorFile expected = sample();
  EXPECT_EQ(back.kind, "weights");
  EXPECT_EQ(back.meta, expected.meta);
  ASSERT_EQ(back.arrays.size(), expected.arrays.size());
  for (size_t i = 0; i < back.arrays.size(); ++i) {
    EXPECT_EQ(back.arrays[i].first, expected.arrays[i].first);
    EXPECT_EQ(back.arrays[i].second.dtype, expected.arrays[i].second.dtype);
    EXPECT_EQ(back.arrays[i].second.shape, expected.arrays[i].second.shape);
    EXPECT_EQ(back.arrays[i].second.bytes, expected.arrays[i].second.bytes);
  }
  EXPECT_EQ(back.find("steps")->data<std::int64_t>()[0], 7);
  EXPECT_EQ(back.find("missing"), nullptr);
  // Every array starts on a 64-byte boundary.
  const nlohmann::json header = headerOf(pc::readTextFile(dir / "a.tensors"));  // kept: the loop borrows from it
  for (const auto& entry : header["arrays"])
    EXPECT_EQ(entry["offset"].get<std::uint64_t>() % 64, 0u) << entry.dump();
}

TEST(TensorFile, NumpyReadsItFromTheLayoutAlone) {
  if (pt::numpyPython().empty()) GTEST_SKIP() << "no python3 with numpy";
  const fs::path dir = pt::freshDir("numpy");
  pc::writeTensorFile(dir / "a.tensors", sample());
  // The layout of core/tensor_file.h, read with struct, json, zlib and numpy only.
  const std::string reader =
      "import json, struct, sys, zlib, numpy\n"
      "b = open(sys.argv[1], 'rb').read()\n"
      "assert b[:8] == b'PXTENSOR'\n"
      "version, size, crc, zero = struct.unpack('<IIII', b[8:24])\n"
      "assert version == 1 and zero == 0 and zlib.crc32(b[24:24 + size]) == crc\n"
      "h = json.loads(b[24:24 + size])\n"
      "assert h['format'] == 'pixelcloth.tensors' and h['kind'] == 'weights'\n"
      "for a in h['arrays']:\n"
      "    raw = b[a['offset']:a['offset'] + a['bytes']]\n"
      "    assert zlib.crc32(raw) == a['crc32']\n"
      "    x = numpy.frombuffer(raw, dtype=a['dtype']).reshape(a['shape'])\n"
      "    print(a['name'], x.dtype.str, x.shape, x.ravel().tolist())\n";
  EXPECT_EQ(pt::runPython(reader, dir / "a.tensors"),
            "0.weight <f4 (2, 3) [1.5, -2.0, 3.0, 4.0, 5.0, 6.25]\n"
            "0.bias <f8 (2,) [0.1, 0.2]\n"
            "steps <i8 () [7]\n"
            "empty <f4 (0, 4) []\n");
}

TEST(TensorFile, AWriterRefusesRepeatedOrEmptyNames) {
  const fs::path dir = pt::freshDir("names");
  pc::TensorFile file = sample();
  file.arrays.push_back(file.arrays.front());
  EXPECT_EQ(pt::inputErrorOf([&] { pc::writeTensorFile(dir / "a.tensors", file); }),
            (dir / "a.tensors").string() + ": array name '0.weight' is empty or repeated");
  EXPECT_FALSE(fs::exists(dir / "a.tensors"));
}

TEST(TensorFile, EveryFaultIsNamedWithTheFile) {
  const fs::path dir = pt::freshDir("faults");
  const fs::path good = dir / "good.tensors";
  pc::writeTensorFile(good, sample());
  const std::string bytes = pc::readTextFile(good);
  const nlohmann::json header = headerOf(bytes);
  const fs::path bad = dir / "bad.tensors";
  auto refusal = [&](const std::string& content, const std::string& kind = "weights") {
    pc::writeTextAtomically(bad, content);
    return pt::inputErrorOf([&] { pc::readTensorFile(bad, kind); });
  };
  auto edited = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json h = header;
    h["meta"].erase("note");  // so that the edited header fits where the old one was
    edit(h);
    return withHeader(bytes, h);
  };
  const std::string name = bad.string();
  struct Case {
    std::string content, kind, message;
  };
  std::string flipped = bytes;
  flipped[header["arrays"][1]["offset"].get<size_t>()] ^= 0x20;
  std::string headerFlipped = bytes;
  headerFlipped[30] ^= 0x01;
  std::string version = bytes;
  version[8] = 2;
  const std::vector<Case> cases = {
      {"", "weights", name + ": 0 bytes, truncated (a pixelcloth tensor file starts with a 24-byte preamble)"},
      {std::string("PK\x03\x04", 4) + std::string(40, '\0'), "checkpoint",
       name + ": a zip file, as LibTorch archives are; pixelcloth's checkpoint files are pixelcloth tensor files "
              "(docs/learning.md), which pixelcloth before 2026-12 did not write: train the model again"},
      {"\x93NUMPY" + bytes.substr(6), "weights", name + ": not a pixelcloth tensor file (it does not start with PXTENSOR)"},
      {version, "weights", name + ": tensor file version 2, this pixelcloth reads version 1"},
      {bytes.substr(0, 100), "weights", name + ": its header claims "},
      {headerFlipped, "weights", name + ": header CRC-32 "},
      {bytes, "checkpoint", name + ": holds weights, expected checkpoint"},
      {bytes.substr(0, header["arrays"][1]["offset"].get<size_t>() + 8), "weights",
       name + ": 0.bias: 16 bytes at offset " + std::to_string(header["arrays"][1]["offset"].get<size_t>()) +
           " are outside the data"},
      {flipped, "weights", name + ": 0.bias: CRC-32 "},
      {edited([](nlohmann::json& h) { h["format"] = 5; }), "weights", name + ": field 'format' is "},
      {edited([](nlohmann::json& h) { h["arrays"] = "none"; }), "weights",
       name + ": field 'arrays' is string, expected an array"},
      {edited([](nlohmann::json& h) { h["arrays"][0]["dtype"] = "<f2"; }), "weights",
       name + ": 0.weight: unsupported dtype '<f2'; expected one of <f4, <f8, <i4, <i8, |u1"},
      {edited([](nlohmann::json& h) { h["arrays"][0]["shape"] = {3, 3}; }), "weights",
       name + ": 0.weight: 24 bytes for shape (3, 3) of <f4, which needs 36"},
      {edited([](nlohmann::json& h) { h["arrays"][0]["shape"] = {-1, 3}; }), "weights",
       name + ": 0.weight: shape [-1,3], expected sizes of 0 or more"},
      {edited([](nlohmann::json& h) { h["arrays"][0]["shape"] = {1ull << 62, 1ull << 62}; }), "weights",
       name + ": 0.weight: shape [4611686018427387904,4611686018427387904] needs more than the 24 bytes given"},
      {edited([](nlohmann::json& h) { h["arrays"][0]["offset"] = 0; }), "weights", name + ": 0.weight: 24 bytes at offset 0 are outside"},
      {edited([](nlohmann::json& h) { h["arrays"][0]["offset"] = 18446744073709551615ull; }), "weights",
       name + ": 0.weight: 24 bytes at offset 18446744073709551615 are outside"},
      {edited([](nlohmann::json& h) { h["arrays"][1]["name"] = "0.weight"; }), "weights",
       name + ": array 2: expected an object with a name of its own"},
      {edited([](nlohmann::json& h) { h["arrays"][1].erase("crc32"); }), "weights",
       name + ": 0.bias: missing field 'crc32'"},
  };
  for (const Case& c : cases) {
    const std::string message = refusal(c.content, c.kind);
    EXPECT_EQ(message.rfind(c.message, 0), 0u) << "expected: " << c.message << "\ngot: " << message;
  }
}

namespace {

std::string withHeader(const std::string& bytes, const nlohmann::json& header) {
  // The edited header must fit where the old one was (the data offsets stay): pad with spaces to the old length.
  std::uint32_t size;
  std::memcpy(&size, bytes.data() + 12, 4);
  std::string text = header.dump();
  EXPECT_LE(text.size(), size) << "the edited header no longer fits";
  text.resize(size, ' ');
  const std::uint32_t crc = static_cast<std::uint32_t>(
      ::crc32(::crc32(0L, nullptr, 0), reinterpret_cast<const unsigned char*>(text.data()), text.size()));
  std::string out = bytes;
  std::memcpy(out.data() + 16, &crc, 4);
  out.replace(24, size, text);
  return out;
}

}  // namespace
