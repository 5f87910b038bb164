// OpenEXR cloth images: exact float round trip with named channels, FLOAT + ZIP on disk, conversion of HALF and
// UINT channels, and the errors for corrupted, truncated and missing files and channels.
#include "pixelcloth/core/exr_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace fs = std::filesystem;

namespace {

// 5 rows x 7 columns (not square, so a transposition shows), values of every sign and magnitude.
pc::ExrImage clothImage() {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  pc::ExrImage image;
  for (const char* name : {"front.du", "front.dv", "mask"}) {
    Eigen::MatrixXf values(5, 7);
    for (int i = 0; i < values.size(); ++i) values.data()[i] = uniform(random) * std::pow(10.0f, (i % 9) - 4);
    image.addChannel(name, values);
  }
  image.channels[2](0, 6) = 42.0f;  // top row, right column
  return image;
}

// Reads the little-endian int32 at `at`.
std::int32_t int32At(const std::string& bytes, size_t at) {
  std::int32_t value;
  std::memcpy(&value, bytes.data() + at, 4);
  return value;
}

}  // namespace

TEST(ExrIo, RoundTripIsExactAndKeepsNames) {
  fs::path dir = pixelcloth::testing::freshDir("roundtrip");
  pc::ExrImage image = clothImage();
  pc::writeExr(dir / "cloth.exr", image);
  pc::ExrImage back = pc::readExr(dir / "cloth.exr");
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  ASSERT_EQ(back.channels.size(), 3u);
  for (size_t c = 0; c < image.channels.size(); ++c) {
    EXPECT_EQ(back.channel(image.channelNames[c]), image.channels[c]) << image.channelNames[c];
  }
  EXPECT_EQ(back.channel("mask")(0, 6), 42.0f);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // no temporary left
}

TEST(ExrIo, ChannelsAreFloatAndZipCompressedOnDisk) {
  fs::path dir = pixelcloth::testing::freshDir("header");
  pc::writeExr(dir / "cloth.exr", clothImage());
  std::string bytes = pc::readTextFile(dir / "cloth.exr");
  ASSERT_EQ(int32At(bytes, 0), 20000630);  // OpenEXR magic
  // Attribute: name \0 type \0 size(int32) value. Compression ZIP_COMPRESSION is 3.
  const std::string compression("compression\0compression\0", 24);
  size_t at = bytes.find(compression);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(int32At(bytes, at + 24), 1);
  EXPECT_EQ(bytes[at + 28], 3);
  // Channel list: per channel name \0, pixel type int32 (FLOAT is 2), 4 bytes, x and y sampling int32.
  const std::string channels("channels\0chlist\0", 16);
  at = bytes.find(channels);
  ASSERT_NE(at, std::string::npos);
  size_t p = at + 16 + 4;
  std::vector<std::string> names;
  while (bytes[p] != '\0') {
    std::string name(bytes.c_str() + p);
    p += name.size() + 1;
    EXPECT_EQ(int32At(bytes, p), 2) << name;
    names.push_back(name);
    p += 16;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"front.du", "front.dv", "mask"}));
}

TEST(ExrIo, HalfAndUintChannelsAreReadAsFloat) {
  pc::ExrImage image = pc::readExr(pixelcloth::testing::asset("half_uint.exr"));
  ASSERT_EQ(image.width, 4);
  ASSERT_EQ(image.height, 3);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) {
      EXPECT_EQ(image.channel("h")(y, x), 0.5f * (4 * y + x));
      EXPECT_EQ(image.channel("u")(y, x), static_cast<float>(4 * y + x));
    }
  }
}

TEST(ExrIo, MissingChannelIsNamedWithThoseThatExist) {
  fs::path dir = pixelcloth::testing::freshDir("missing");
  pc::writeExr(dir / "cloth.exr", clothImage());
  pc::ExrImage image = pc::readExr(dir / "cloth.exr");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { image.channel("back.dn"); }),
            (dir / "cloth.exr").string() + ": no channel 'back.dn'; the channels are 'front.du', 'front.dv', 'mask'");
  EXPECT_TRUE(image.hasChannel("mask"));
  EXPECT_FALSE(image.hasChannel("back.dn"));
}

TEST(ExrIo, TruncatedGarbageAndMissingFilesAreNamed) {
  fs::path dir = pixelcloth::testing::freshDir("corrupt");
  pc::ExrImage big;
  big.addChannel("du", Eigen::MatrixXf::Random(64, 64));
  big.addChannel("dv", Eigen::MatrixXf::Random(64, 64));
  pc::writeExr(dir / "whole.exr", big);
  std::string bytes = pc::readTextFile(dir / "whole.exr");
  for (size_t keep : {bytes.size() / 2, bytes.size() - 10, size_t{40}}) {
    std::ofstream(dir / "cut.exr", std::ios::binary) << bytes.substr(0, keep);
    std::string message = pixelcloth::testing::inputErrorOf([&] { pc::readExr(dir / "cut.exr"); });
    EXPECT_EQ(message.rfind((dir / "cut.exr").string() + ": ", 0), 0u) << "kept " << keep << ": " << message;
  }
  std::string garbage;
  for (int i = 0; i < 1000; ++i) garbage.push_back(static_cast<char>(i * 31 + 7));
  std::ofstream(dir / "garbage.exr", std::ios::binary) << garbage;
  std::string message = pixelcloth::testing::inputErrorOf([&] { pc::readExr(dir / "garbage.exr"); });
  EXPECT_EQ(message.rfind((dir / "garbage.exr").string() + ": not a readable OpenEXR file", 0), 0u) << message;
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::readExr(dir / "absent.exr"); }),
            (dir / "absent.exr").string() + ": no such file");
}

TEST(ExrIo, InconsistentImagesAreRefused) {
  fs::path dir = pixelcloth::testing::freshDir("inconsistent");
  pc::ExrImage image;
  image.addChannel("du", Eigen::MatrixXf::Zero(4, 6));
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { image.addChannel("dv", Eigen::MatrixXf::Zero(6, 4)); }),
            "image channel 'dv' is 6 x 4 (rows x columns), expected 4 x 6");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { image.addChannel("du", Eigen::MatrixXf::Zero(4, 6)); }),
            "image already has a channel 'du'");
  image.channels[0].resize(3, 6);  // broken behind addChannel's back
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] {
              pc::writeExr(dir / "bad.exr", image);
            }).find("channel 'du' is 3 x 6, expected 4 x 6"),
            std::string::npos);
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] {
              pc::writeExr(dir / "empty.exr", pc::ExrImage{});
            }).find("without channels"),
            std::string::npos);
  EXPECT_TRUE(fs::is_empty(dir));
}

// A few bytes of header can declare a huge data window: the size is checked before anything is allocated for it
// (fuzzing found headers that made the reader zero gigabytes before it noticed the file held none of those pixels).
TEST(ExrIo, AHeaderDeclaringMoreThanAGibibyteIsRefusedBeforeAllocating) {
  fs::path dir = pixelcloth::testing::freshDir("hugewindow");
  pc::ExrImage image;
  image.addChannel("du", Eigen::MatrixXf::Random(64, 64));
  image.addChannel("dv", Eigen::MatrixXf::Random(64, 64));
  pc::writeExr(dir / "small.exr", image);
  std::string bytes = pc::readTextFile(dir / "small.exr");
  const std::string attribute("dataWindow\0box2i\0", 17);
  const size_t at = bytes.find(attribute);
  ASSERT_NE(at, std::string::npos);
  const size_t box = at + attribute.size() + 4;  // after the attribute's size
  ASSERT_EQ(int32At(bytes, box + 8), 63);        // xMax of the 64 x 64 window
  const std::int32_t last = 16383;               // 16384 x 16384 x 2 channels = 2^29 values
  std::memcpy(&bytes[box + 8], &last, 4);
  std::memcpy(&bytes[box + 12], &last, 4);
  std::ofstream(dir / "huge.exr", std::ios::binary) << bytes;
  std::string message = pixelcloth::testing::inputErrorOf([&] { pc::readExr(dir / "huge.exr"); });
  EXPECT_EQ(message, (dir / "huge.exr").string() +
                         ": the image is 16384 x 16384 with 2 channels, more than the 268435456 values (1 GiB as "
                         "floats) supported")
      << message;
}
