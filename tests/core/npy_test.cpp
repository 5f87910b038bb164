// NumPy .npy files: round trips of every supported dtype, each malformed input's error, and numpy itself as an
// independent reader and writer (skipped when python3 or numpy is missing).
#include "pixelcloth/core/npy.h"

#include <gtest/gtest.h>

#include <limits>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "support/python.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace fs = std::filesystem;

namespace {

// A .npy file with a hand-written header (version 1.0, padded to 64 bytes) and `data` after it.
fs::path writeRawNpy(const fs::path& path, const std::string& dict, const std::string& data, char major = 1) {
  std::string header = dict;
  const size_t preamble = major == 1 ? 10 : 12;
  header.append((64 - (preamble + header.size() + 1) % 64) % 64, ' ');
  header += '\n';
  std::string bytes("\x93NUMPY", 6);
  bytes += major;
  bytes += '\0';
  for (size_t i = 0; i < preamble - 8; ++i) bytes += static_cast<char>((header.size() >> (8 * i)) & 0xff);
  std::ofstream(path, std::ios::binary) << bytes << header << data;
  return path;
}

std::string floats(std::initializer_list<float> values) {
  return std::string(reinterpret_cast<const char*>(values.begin()), values.size() * sizeof(float));
}

}  // namespace

TEST(Npy, RoundTripOfEveryDtypeAndShape) {
  fs::path dir = pixelcloth::testing::freshDir("roundtrip");
  pc::writeNpy(dir / "f4.npy", std::vector<float>{1.5f, -2.25f, 3e-20f, 4e20f, 0, -0.0f}, {2, 3});
  pc::writeNpy(dir / "f8.npy", std::vector<double>{0.1, 1e300, -7}, {3});
  pc::writeNpy(dir / "i4.npy", std::vector<std::int32_t>{-2147483647 - 1, 2147483647, 0, 5}, {2, 1, 2});
  pc::writeNpy(dir / "i8.npy", std::vector<std::int64_t>{-(std::int64_t{1} << 62), 3}, {2});
  pc::writeNpy(dir / "u1.npy", std::vector<std::uint8_t>{0, 255, 7}, {3});
  pc::writeNpy(dir / "scalar.npy", std::vector<double>{2.5}, {});
  pc::writeNpy(dir / "empty.npy", std::vector<float>{}, {0, 4});

  pc::NpyArray f4 = pc::readNpy(dir / "f4.npy");
  EXPECT_EQ(f4.dtype, "<f4");
  EXPECT_EQ(f4.shape, (std::vector<std::int64_t>{2, 3}));
  EXPECT_EQ(std::vector<float>(f4.data<float>(), f4.data<float>() + 6),
            (std::vector<float>{1.5f, -2.25f, 3e-20f, 4e20f, 0, -0.0f}));
  EXPECT_EQ(pc::readNpy(dir / "f8.npy").data<double>()[1], 1e300);
  pc::NpyArray i4 = pc::readNpy(dir / "i4.npy");
  EXPECT_EQ(i4.shape, (std::vector<std::int64_t>{2, 1, 2}));
  EXPECT_EQ(i4.data<std::int32_t>()[0], -2147483647 - 1);
  EXPECT_EQ(pc::readNpy(dir / "i8.npy").data<std::int64_t>()[0], -(std::int64_t{1} << 62));
  EXPECT_EQ(pc::readNpy(dir / "u1.npy").data<std::uint8_t>()[1], 255);
  pc::NpyArray scalar = pc::readNpy(dir / "scalar.npy");
  EXPECT_TRUE(scalar.shape.empty());
  EXPECT_EQ(scalar.size(), 1);
  EXPECT_EQ(scalar.data<double>()[0], 2.5);
  EXPECT_EQ(pc::readNpy(dir / "empty.npy").size(), 0);

  // The data of every file starts on a 64-byte boundary, as numpy writes it.
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::string bytes = pc::readTextFile(entry.path());
    size_t dataStart = bytes.find('\n') + 1;
    EXPECT_EQ(dataStart % 64, 0u) << entry.path();
  }
}

TEST(Npy, MatricesKeepRowsAndColumns) {
  fs::path dir = pixelcloth::testing::freshDir("matrix");
  Eigen::MatrixXf m(2, 3);
  m << 1, 2, 3, 4, 5, 6;
  pc::writeNpy(dir / "m.npy", m);
  pc::NpyArray raw = pc::readNpy(dir / "m.npy");
  EXPECT_EQ(raw.shape, (std::vector<std::int64_t>{2, 3}));
  EXPECT_EQ(raw.data<float>()[1], 2.0f);  // C order: the first row comes first
  EXPECT_EQ(pc::readNpyMatrixF(dir / "m.npy", 2, 3), m);
  Eigen::MatrixXd d = m.cast<double>();
  pc::writeNpy(dir / "d.npy", d);
  EXPECT_EQ(pc::readNpyMatrixD(dir / "d.npy"), d);
  Eigen::MatrixXi i = m.cast<int>();
  pc::writeNpy(dir / "i.npy", i);
  EXPECT_EQ(pc::readNpyMatrixI(dir / "i.npy", -1, 3), i);
}

TEST(Npy, MatrixDtypeAndShapeAreChecked) {
  fs::path dir = pixelcloth::testing::freshDir("check");
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(100, 12);  // a concrete matrix: an expression is ambiguous
  pc::writeNpy(dir / "weights.npy", weights);
  std::string file = (dir / "weights.npy").string();
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::readNpyMatrixF(dir / "weights.npy"); }),
            file + ": dtype <f8, expected float32 <f4");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::readNpyMatrixD(dir / "weights.npy", 15204, 12); }),
            file + ": shape (100, 12), expected (15204, 12)");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::readNpyMatrixD(dir / "weights.npy", -1, 3); }),
            file + ": shape (100, 12), expected (any, 3)");
  pc::writeNpy(dir / "flat.npy", std::vector<double>(5, 1.0), {5});
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::readNpyMatrixD(dir / "flat.npy"); }),
            (dir / "flat.npy").string() + ": shape (5,), expected (any, any)");
  pc::NpyArray array = pc::readNpy(dir / "weights.npy");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { array.data<std::int64_t>(); }),
            file + ": dtype <f8, expected int64 <i8");
}

TEST(Npy, MatricesWithNanOrInfinityAreRefusedAtTheFirstBadValue) {
  fs::path dir = pixelcloth::testing::freshDir("nonfinite");
  Eigen::MatrixXf offsets = Eigen::MatrixXf::Ones(6, 3);
  offsets(4, 1) = std::numeric_limits<float>::quiet_NaN();
  offsets(5, 0) = std::numeric_limits<float>::infinity();
  pc::writeNpy(dir / "values.npy", offsets);
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::readNpyMatrixF(dir / "values.npy", 6, 3); }),
            (dir / "values.npy").string() + ": row 5, column 2 (counting from 1) is nan; expected finite numbers");
  Eigen::MatrixXd infinite = Eigen::MatrixXd::Zero(2, 2);
  infinite(1, 1) = -std::numeric_limits<double>::infinity();
  pc::writeNpy(dir / "d.npy", infinite);
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] { pc::readNpyMatrixD(dir / "d.npy"); }).find("row 2, column 2"),
            std::string::npos);
}

TEST(Npy, MalformedFilesAreRefusedWithTheirFault) {
  fs::path dir = pixelcloth::testing::freshDir("malformed");
  auto errorOf = [&](const fs::path& path) { return pixelcloth::testing::inputErrorOf([&] { pc::readNpy(path); }); };
  auto file = [&](const char* name) { return (dir / name).string(); };
  const std::string two = floats({1, 2});

  // The reference: a hand-written well-formed file, also in format version 2.0, is accepted.
  writeRawNpy(dir / "ok.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (2,), }", two);
  EXPECT_EQ(pc::readNpy(dir / "ok.npy").data<float>()[1], 2.0f);
  writeRawNpy(dir / "v2.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (2,), }", two, 2);
  EXPECT_EQ(pc::readNpy(dir / "v2.npy").data<float>()[1], 2.0f);

  EXPECT_EQ(
      errorOf(writeRawNpy(dir / "fortran.npy", "{'descr': '<f4', 'fortran_order': True, 'shape': (2,), }", two)),
      file("fortran.npy") + ": fortran_order is True; expected C order (in numpy, save numpy.ascontiguousarray(a))");
  EXPECT_EQ(errorOf(writeRawNpy(dir / "big.npy", "{'descr': '>f4', 'fortran_order': False, 'shape': (2,), }", two)),
            file("big.npy") + ": dtype >f4 is big-endian; expected little-endian (in numpy, save a.astype('<f4'))");
  EXPECT_EQ(errorOf(writeRawNpy(dir / "complex.npy", "{'descr': '<c8', 'fortran_order': False, 'shape': (1,), }", two)),
            file("complex.npy") + ": unsupported dtype '<c8'; expected one of <f4, <f8, <i4, <i8, |u1");
  EXPECT_EQ(errorOf(writeRawNpy(dir / "short.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (3,), }", two)),
            file("short.npy") + ": truncated: shape (3,) of <f4 needs 12 bytes of data, the file has 8");
  EXPECT_EQ(errorOf(writeRawNpy(dir / "long.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (1,), }", two)),
            file("long.npy") +
                ": 4 bytes after the data that shape (1,) of <f4 needs; the file is not a single .npy "
                "array");
  std::string noShape = errorOf(writeRawNpy(dir / "noshape.npy", "{'descr': '<f4', 'fortran_order': False, }", two));
  EXPECT_EQ(noShape.rfind(file("noshape.npy") + ": malformed npy header: expected the keys", 0), 0u) << noShape;
  std::string badTuple =
      errorOf(writeRawNpy(dir / "badtuple.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (2, -1), }", two));
  EXPECT_EQ(badTuple.rfind(file("badtuple.npy") + ": malformed npy header at character", 0), 0u) << badTuple;
  std::string notDict = errorOf(writeRawNpy(dir / "notdict.npy", "[1, 2]", two));
  EXPECT_EQ(notDict.rfind(file("notdict.npy") + ": malformed npy header", 0), 0u) << notDict;

  std::ofstream(dir / "magic.npy", std::ios::binary) << "PK\x03\x04 this is a zip (an .npz), not an .npy";
  EXPECT_EQ(errorOf(dir / "magic.npy"), file("magic.npy") + ": not a NumPy .npy file (bad magic: expected \\x93NUMPY)");
  std::string whole = pc::readTextFile(dir / "ok.npy");
  std::ofstream(dir / "cut.npy", std::ios::binary) << whole.substr(0, 30);
  EXPECT_EQ(errorOf(dir / "cut.npy"), file("cut.npy") + ": truncated: the header needs 128 bytes, the file has 30");
  EXPECT_EQ(errorOf(dir / "absent.npy"), file("absent.npy") + ": no such file");
}

TEST(Npy, WritingInconsistentArraysIsRefused) {
  fs::path dir = pixelcloth::testing::freshDir("write");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] {
              pc::writeNpy(dir / "a.npy", std::vector<float>(5), {2, 3});
            }),
            "npy array: 5 values for shape (2, 3) (6 elements)");
  pc::NpyArray array{"<f2", {1}, {0, 0}, {}};
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::writeNpy(dir / "b.npy", array); }),
            (dir / "b.npy").string() + ": unsupported dtype '<f2'; expected one of <f4, <f8, <i4, <i8, |u1");
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Npy, NumpyReadsOurFiles) {
  if (pixelcloth::testing::numpyPython().empty()) GTEST_SKIP() << "no python3 with numpy";
  fs::path dir = pixelcloth::testing::freshDir("numpyreads");
  Eigen::MatrixXf m(2, 3);
  m << 1.5f, -2, 3, 4, 5, 6.25f;
  pc::writeNpy(dir / "m.npy", m);
  EXPECT_EQ(pixelcloth::testing::runPython("import sys, numpy\na = numpy.load(sys.argv[1])\n"
                      "print(a.dtype.str, a.shape, a.flags['C_CONTIGUOUS'], a[0, 0], a[0, 2], a[1, 2])\n",
                      dir / "m.npy"),
            "<f4 (2, 3) True 1.5 3.0 6.25\n");
  pc::writeNpy(dir / "i8.npy", std::vector<std::int64_t>{-(std::int64_t{1} << 40), 7, 8, 9}, {2, 1, 2});
  EXPECT_EQ(
      pixelcloth::testing::runPython("import sys, numpy\na = numpy.load(sys.argv[1])\nprint(a.dtype.str, a.shape, a[0, 0, 0], a[1, 0, 1])\n",
                dir / "i8.npy"),
      "<i8 (2, 1, 2) -1099511627776 9\n");
  pc::writeNpy(dir / "u1.npy", std::vector<std::uint8_t>{0, 200}, {2});
  EXPECT_EQ(pixelcloth::testing::runPython("import sys, numpy\na = numpy.load(sys.argv[1])\nprint(a.dtype.str, a.shape, a.tolist())\n",
                      dir / "u1.npy"),
            "|u1 (2,) [0, 200]\n");
  pc::writeNpy(dir / "s.npy", std::vector<double>{0.1}, {});
  EXPECT_EQ(pixelcloth::testing::runPython("import sys, numpy\na = numpy.load(sys.argv[1])\nprint(a.dtype.str, a.shape, repr(float(a)))\n",
                      dir / "s.npy"),
            "<f8 () 0.1\n");
}

TEST(Npy, WeReadWhatNumpyWrites) {
  if (pixelcloth::testing::numpyPython().empty()) GTEST_SKIP() << "no python3 with numpy";
  fs::path dir = pixelcloth::testing::freshDir("numpywrites");
  ASSERT_EQ(pixelcloth::testing::runPython("import sys, numpy\n"
                      "d = sys.argv[1]\n"
                      "numpy.save(d + '/f4.npy', numpy.arange(12, dtype='<f4').reshape(3, 4) / 8)\n"
                      "numpy.save(d + '/i4.npy', numpy.array([[-5, 6]], dtype='<i4'))\n"
                      "numpy.save(d + '/u1.npy', numpy.array([1, 254], dtype=numpy.uint8))\n"
                      "numpy.save(d + '/fortran.npy', numpy.asfortranarray(numpy.ones((2, 3), dtype='<f4')))\n"
                      "numpy.save(d + '/big.npy', numpy.ones(3, dtype='>f8'))\n"
                      "print('ok')\n",
                      dir),
            "ok\n");
  Eigen::MatrixXf f4 = pc::readNpyMatrixF(dir / "f4.npy", 3, 4);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(f4(r, c), (4 * r + c) / 8.0f);
  Eigen::MatrixXi i4 = pc::readNpyMatrixI(dir / "i4.npy", 1, 2);
  EXPECT_EQ(i4(0, 0), -5);
  EXPECT_EQ(i4(0, 1), 6);
  pc::NpyArray u1 = pc::readNpy(dir / "u1.npy");
  EXPECT_EQ(u1.dtype, "|u1");
  EXPECT_EQ(u1.data<std::uint8_t>()[1], 254);
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] { pc::readNpy(dir / "fortran.npy"); }).find("fortran_order is True"),
            std::string::npos);
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] { pc::readNpy(dir / "big.npy"); }).find("dtype >f8 is big-endian"),
            std::string::npos);
}
