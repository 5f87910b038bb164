// Cloth image editing (paper appendix B).
#include "pixelcloth/patches/edit.h"

#include <gtest/gtest.h>

#include "pixelcloth/core/image.h"
#include "support/test_util.h"

namespace pp = pixelcloth::patches;
namespace pc = pixelcloth::core;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

namespace {

/// A 2-layer 32 x 16 image: left half of each layer inside, the column next to it padding, the rest empty;
/// du = x, dv = y, dn = 0.01.
pp::ClothImage testImage() {
  pp::ClothImage image;
  image.width = 32;
  image.height = 16;
  for (const char* name : {"front", "back"}) {
    pp::ClothLayer l;
    l.name = name;
    l.du.resize(16, 32);
    l.dv.resize(16, 32);
    l.dn = Eigen::MatrixXf::Constant(16, 32, 0.01f);
    l.mask = Eigen::MatrixXf::Zero(16, 32);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 32; ++x) {
        l.du(y, x) = x;
        l.dv(y, x) = y;
        l.mask(y, x) = x < 16 ? 2 : x == 16 ? 1 : 0;
      }
    l.dn = (l.mask.array() > 0).select(l.dn, 0.0f);
    image.layers.push_back(l);
  }
  return image;
}

}  // namespace

TEST(Edit, ShiftChangesDuDvOnlyInsideTheRegion) {
  pp::ClothImage image = testImage(), before = image;
  Eigen::MatrixXf region = Eigen::MatrixXf::Zero(16, 32);
  region.block(0, 0, 8, 32).setOnes();  // top half of every layer
  pp::shiftImage(image, 0.5f, -0.25f, region);
  for (size_t l = 0; l < 2; ++l)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 32; ++x) {
        bool edited = y < 8 && before.layers[l].mask(y, x) > 0;
        EXPECT_FLOAT_EQ(image.layers[l].du(y, x), before.layers[l].du(y, x) + (edited ? 0.5f : 0.0f));
        EXPECT_FLOAT_EQ(image.layers[l].dv(y, x), before.layers[l].dv(y, x) - (edited ? 0.25f : 0.0f));
        EXPECT_EQ(image.layers[l].dn(y, x), before.layers[l].dn(y, x));
        EXPECT_EQ(image.layers[l].mask(y, x), before.layers[l].mask(y, x));
      }
  // A side-by-side region (64 wide) addresses the back layer alone.
  pp::ClothImage side = testImage();
  Eigen::MatrixXf backOnly = Eigen::MatrixXf::Zero(16, 64);
  backOnly.rightCols(32).setOnes();
  pp::shiftImage(side, 1.0f, 0.0f, backOnly);
  EXPECT_EQ(side.layers[0].du, before.layers[0].du);
  EXPECT_FLOAT_EQ(side.layers[1].du(3, 3), before.layers[1].du(3, 3) + 1.0f);
}

TEST(Edit, InflateScalesAndAddsToDn) {
  pp::ClothImage image = testImage();
  pp::inflateImage(image, 2.0f, 0.005f);
  EXPECT_FLOAT_EQ(image.layers[0].dn(4, 4), 0.025f);
  EXPECT_FLOAT_EQ(image.layers[1].dn(4, 16), 0.025f);  // padding too
  EXPECT_EQ(image.layers[0].dn(4, 20), 0.0f);          // empty stays empty
  EXPECT_FLOAT_EQ(image.layers[0].du(4, 4), 4.0f);
}

TEST(Edit, BrushPeaksAtTheCentreAndFadesToZero) {
  pp::ClothImage image = testImage(), before = image;
  pp::brushImage(image, {32 + 8, 7, 5, 0.02f});  // centre of the back layer's inside part
  Eigen::MatrixXf added = image.layers[1].dn - before.layers[1].dn;
  EXPECT_FLOAT_EQ(added(7, 8), 0.02f);
  EXPECT_FLOAT_EQ(added.maxCoeff(), 0.02f);
  EXPECT_EQ(added(7, 13), 0.0f);  // at the radius
  EXPECT_GT(added(7, 10), added(7, 11));
  EXPECT_EQ(image.layers[0].dn, before.layers[0].dn);
  EXPECT_NE(inputErrorOf([&] { pp::brushImage(image, {100, 7, 5, 0.02f}); }).find("outside"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { pp::brushImage(image, {8, 7, 0, 0.02f}); }).find("radius"), std::string::npos);
}

TEST(Edit, BlendWithMaskZeroOrOneGivesEitherImage) {
  pp::ClothImage a = testImage(), b = testImage();
  pp::shiftImage(b, 3.0f, 4.0f);
  pp::inflateImage(b, 1.0f, 0.02f);
  pp::ClothImage keep = a, take = a, half = a;
  pp::blendImages(keep, b, Eigen::MatrixXf::Zero(16, 32));
  pp::blendImages(take, b, Eigen::MatrixXf::Ones(16, 32));
  pp::blendImages(half, b, Eigen::MatrixXf::Constant(16, 32, 0.5f));
  for (size_t l = 0; l < 2; ++l) {
    EXPECT_EQ(keep.layers[l].du, a.layers[l].du);
    EXPECT_EQ(keep.layers[l].dn, a.layers[l].dn);
    EXPECT_EQ(take.layers[l].du, b.layers[l].du);
    EXPECT_EQ(take.layers[l].dv, b.layers[l].dv);
    EXPECT_EQ(take.layers[l].dn, b.layers[l].dn);
    EXPECT_FLOAT_EQ(half.layers[l].du(2, 2), 2.0f + 1.5f);
  }
  pp::ClothImage other = testImage();
  other.layers[1].name = "side";
  other.source = "other.exr";
  std::string message = inputErrorOf([&] { pp::blendImages(a, other, Eigen::MatrixXf::Ones(16, 32)); });
  EXPECT_NE(message.find("other.exr"), std::string::npos) << message;
  EXPECT_NE(inputErrorOf([&] { pp::blendImages(a, b, Eigen::MatrixXf::Ones(5, 5)); }).find("region"),
            std::string::npos);
}

TEST(Edit, MaskPngMustHaveTheImageSize) {
  auto dir = freshDir("mask");
  pp::ClothImage image = testImage();
  pc::RgbImage png(32, 16, {0, 0, 0});
  png.set(3, 2, {255, 255, 255});
  pc::writePng(dir / "m.png", png);
  Eigen::MatrixXf alpha = pp::readEditMask(dir / "m.png", image);
  EXPECT_EQ(alpha(2, 3), 1.0f);
  EXPECT_EQ(alpha(0, 0), 0.0f);
  pc::writePng(dir / "wrong.png", pc::RgbImage(10, 10));
  EXPECT_NE(inputErrorOf([&] { pp::readEditMask(dir / "wrong.png", image); }).find("wrong.png"), std::string::npos);
}
