// Whole-garment cloth images, EXR files and previews, and patch crops.
#include "pixelcloth/patches/cloth_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>

#include "pixelcloth/garment/garment.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace pp = pixelcloth::patches;
namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;
using pixelcloth::testing::smoothOffsets;

namespace {
const pixelcloth::garment::Garment& shirt() { return pixelcloth::testing::tshirt(); }

const pp::ClothImager& shirtImager() {
  static const pp::ClothImager imager(shirt());
  return imager;
}

}  // namespace

TEST(ClothImage, FrameOfSquareImageIsTheLayoutFrame) {
  for (int l = 0; l < 2; ++l) {
    pp::ImageFrame a = pp::clothImageFrame(shirt(), l, 256, 256), b = pp::layoutFrame(shirt(), l, 256);
    EXPECT_NEAR(a.metresPerPixel, b.metresPerPixel, 1e-15);
    EXPECT_NEAR((a.topLeft - b.topLeft).norm(), 0, 1e-12);
  }
}

TEST(ClothImage, ConstantOffsetsComeBackExactlyAndSeamVerticesAverage) {
  const pp::ClothImager& imager = shirtImager();
  EXPECT_EQ(imager.width(), 256);
  Eigen::MatrixXf constant = Eigen::MatrixXf::Zero(shirt().mesh.numVertices(), 3);
  constant.col(0).setConstant(0.01f);
  constant.col(1).setConstant(-0.02f);
  constant.col(2).setConstant(0.03f);
  pp::ClothImage image = imager.rasterize(constant);
  ASSERT_EQ(image.layers.size(), 2u);
  EXPECT_EQ(image.layers[0].name, "front");
  EXPECT_EQ(image.layers[1].name, "back");
  EXPECT_LT((imager.sample(image) - constant).cwiseAbs().maxCoeff(), 1e-6);
  // A seam vertex (in both layouts) gets the average of its two layouts' samples.
  pp::ClothImage split = image;
  split.layers[1].du.setConstant(0.03f);
  Eigen::MatrixXf back = imager.sample(split);
  int seamVertices = 0;
  for (int v = 0; v < shirt().mesh.numVertices(); ++v) {
    bool front = shirt().vertexUV(v, 0) >= 0, rear = shirt().vertexUV(v, 1) >= 0;
    float expected = front && rear ? 0.02f : front ? 0.01f : 0.03f;
    seamVertices += front && rear;
    ASSERT_NEAR(back(v, 0), expected, 1e-6) << "vertex " << v;
  }
  EXPECT_GT(seamVertices, 50);
}

TEST(ClothImage, SmoothOffsetsRoundTripWithinAFractionOfAMillimetre) {
  Eigen::MatrixXf x = smoothOffsets(shirt());
  Eigen::MatrixXf back = shirtImager().sample(shirtImager().rasterize(x));
  double worst = (back - x).cwiseAbs().maxCoeff();
  std::cout << "[cloth image 256 round trip] max error " << worst * 1e3 << " mm\n";
  EXPECT_LT(worst, 2e-4);  // 0.2 mm on centimetre offsets
}

TEST(ClothImage, ExrRoundTripKeepsEveryChannel) {
  auto dir = freshDir("exr");
  pp::ClothImage image = shirtImager().rasterize(smoothOffsets(shirt()));
  pp::writeClothImage(dir / "cloth.exr", image);
  pp::ClothImage read = pp::readClothImage(dir / "cloth.exr");
  ASSERT_EQ(read.layers.size(), 2u);
  EXPECT_EQ(read.width, 256);
  for (size_t l = 0; l < 2; ++l) {
    EXPECT_EQ(read.layers[l].name, image.layers[l].name);
    EXPECT_EQ(read.layers[l].du, image.layers[l].du);
    EXPECT_EQ(read.layers[l].dv, image.layers[l].dv);
    EXPECT_EQ(read.layers[l].dn, image.layers[l].dn);
    EXPECT_EQ(read.layers[l].mask, image.layers[l].mask);
  }
  pc::ExrImage exr = pc::readExr(dir / "cloth.exr");
  for (const char* name :
       {"front.du", "front.dv", "front.dn", "front.mask", "back.du", "back.dv", "back.dn", "back.mask"})
    EXPECT_TRUE(exr.hasChannel(name)) << name;
}

TEST(ClothImage, BadFilesAreRefusedNamingTheFile) {
  auto dir = freshDir("bad");
  pp::ClothImage image = shirtImager().rasterize(smoothOffsets(shirt()));
  pp::writeClothImage(dir / "good.exr", image);
  std::string bytes;
  {
    std::ifstream in(dir / "good.exr", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::ofstream(dir / "truncated.exr", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_NE(inputErrorOf([&] { pp::readClothImage(dir / "truncated.exr"); }).find("truncated.exr"), std::string::npos);
  // Missing channel.
  pc::ExrImage exr = image.toExr();
  pc::ExrImage partial;
  for (size_t c = 0; c < exr.channels.size(); ++c)
    if (exr.channelNames[c] != "back.dn") partial.addChannel(exr.channelNames[c], exr.channels[c]);
  pc::writeExr(dir / "partial.exr", partial);
  std::string message = inputErrorOf([&] { pp::readClothImage(dir / "partial.exr"); });
  EXPECT_NE(message.find("partial.exr"), std::string::npos) << message;
  EXPECT_NE(message.find("back.dn"), std::string::npos) << message;
  // A cloth image of the wrong size for the garment.
  pp::ClothImager small(shirt(), {128, 128});
  pp::writeClothImage(dir / "small.exr", small.rasterize(smoothOffsets(shirt())));
  pp::ClothImage read = pp::readClothImage(dir / "small.exr");
  message = inputErrorOf([&] { shirtImager().sample(read); });
  EXPECT_NE(message.find("small.exr"), std::string::npos) << message;
  // Wrong vertex count.
  message = inputErrorOf([&] { shirtImager().rasterize(Eigen::MatrixXf::Zero(10, 3)); });
  EXPECT_NE(message.find("10 x 3"), std::string::npos) << message;
}

TEST(ClothImage, NecktieIsPortrait64By256) {
  pg::Garment tie = pg::makeNecktie();
  pp::ClothImager imager(tie);
  EXPECT_EQ(imager.width(), 64);
  EXPECT_EQ(imager.height(), 256);
  const pp::ImageFrame& frame = imager.raster(0).frame;
  Eigen::AlignedBox2d box = tie.layoutBounds(0);
  for (Eigen::Vector2d corner : {box.min(), box.max()}) {
    Eigen::Vector2d p = frame.toPixel(corner);
    EXPECT_GE(p.x(), 0);
    EXPECT_LE(p.x(), 64);
    EXPECT_GE(p.y(), 0);
    EXPECT_LE(p.y(), 256);
  }
  // The tie spans the height the frame margin leaves.
  EXPECT_GT(box.sizes().y() / frame.metresPerPixel, (1.0 - 2.0 * pp::kLayoutMargin - 0.02) * 256);
  Eigen::MatrixXf x = smoothOffsets(tie);
  pp::ClothImage image = imager.rasterize(x);
  ASSERT_EQ(image.layers.size(), 1u);
  EXPECT_EQ(image.layers[0].du.rows(), 256);
  EXPECT_EQ(image.layers[0].du.cols(), 64);
  EXPECT_LT((imager.sample(image) - x).cwiseAbs().maxCoeff(), 2e-4);
  // Unprefixed channels ("du dv dn mask") are accepted for a one-layout garment.
  pp::ClothImage plain = image;
  plain.layers[0].name = "";
  EXPECT_LT((imager.sample(plain) - x).cwiseAbs().maxCoeff(), 2e-4);
}

TEST(ClothImage, PatchCropsCentreThePatchAndMatchTheFullImage) {
  std::vector<std::pair<int, int>> cuts;
  for (const pg::Seam& seam : shirt().seams)
    if (!seam.joinsLayouts)
      for (size_t i = 0; i + 1 < seam.vertices.size(); ++i) cuts.emplace_back(seam.vertices[i], seam.vertices[i + 1]);
  std::vector<pp::Patch> patches = pp::segmentPatches(shirt(), cuts);
  ASSERT_EQ(patches.size(), 6u);
  Eigen::MatrixXf x = smoothOffsets(shirt());
  for (const pp::Patch& patch : patches) {
    if (patch.faces.size() > 1500) continue;  // the torso does not fit 160 px; the sleeves do
    pp::PatchCrop crop = pp::cropFrame(shirt(), patch, 512, 160);
    pp::ImageFrame full = pp::layoutFrame(shirt(), patch.layout, 512);
    EXPECT_EQ(crop.frame.metresPerPixel, full.metresPerPixel);
    EXPECT_EQ(crop.frame.width, 160);
    // The patch's vertices lie inside the crop, roughly centred.
    Eigen::AlignedBox2d box;
    for (int v : patch.vertices)
      box.extend(crop.frame.toPixel(shirt().mesh.UV.row(shirt().vertexUV(v, patch.layout)).transpose()));
    EXPECT_GE(box.min().minCoeff(), 0);
    EXPECT_LE(box.max().maxCoeff(), 160);
    EXPECT_LT((box.center() - Eigen::Vector2d(80, 80)).cwiseAbs().maxCoeff(), 1.0);
    // Inside pixels equal the full image's pixels at the same place; padding pixels exist; other pixels are empty.
    pp::RasterOperator fullRaster = pp::buildRaster(shirt(), patch.layout, full);
    Eigen::MatrixXf a = crop.raster.apply(x), b = fullRaster.apply(x);
    int in = 0;
    for (int y = 0; y < 160; ++y)
      for (int xx = 0; xx < 160; ++xx) {
        size_t i = size_t(y) * 160 + xx;
        if (crop.raster.mask[i] != uint8_t(pp::PixelClass::Inside)) continue;
        int fx = xx + crop.origin.x(), fy = y + crop.origin.y();
        ASSERT_TRUE(fx >= 0 && fy >= 0 && fx < 512 && fy < 512);
        ++in;
        ASSERT_NEAR(a(i, 0), b(size_t(fy) * 512 + fx, 0), 1e-6);
      }
    EXPECT_GT(in, 100);
    EXPECT_GT(crop.raster.count(pp::PixelClass::Padding), 100);
    // Only the patch's vertices have non-zero columns.
    std::set<int> own(patch.vertices.begin(), patch.vertices.end());
    for (int k = 0; k < crop.raster.matrix.outerSize(); ++k)
      for (pp::SparseOperator::InnerIterator it(crop.raster.matrix, k); it; ++it) ASSERT_TRUE(own.count(it.col()));
  }
}
