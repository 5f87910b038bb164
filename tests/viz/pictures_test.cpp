// The pictures of the stages: the pattern, text, the basis figures, the patches.
#include "pixelcloth/viz/pictures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/cloth_image.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/viz/basis_figures.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/patch_picture.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace pb = pixelcloth::body;
namespace pc = pixelcloth::core;
namespace pcg = pixelcloth::cage;
namespace pg = pixelcloth::garment;
namespace pp = pixelcloth::patches;
namespace pv = pixelcloth::viz;

namespace {
const pg::Garment& shirt() { return pixelcloth::testing::tshirt(); }

const pg::Garment& tie() {
  static const pg::Garment garment = pg::makeNecktie();
  return garment;
}

const std::vector<pp::Patch>& shirtPatches() {
  static const std::vector<pp::Patch> patches =
      pp::garmentPatches(shirt());
  return patches;
}
using pixelcloth::testing::inputErrorOf;
using pixelcloth::testing::smoothOffsets;
}  // namespace

TEST(Garment, RenderPatternDrawsLayoutsSideBySide) {
  const int ppm = 500;
  pc::RgbImage image = pv::renderPattern(shirt(), ppm);
  const double width = shirt().layoutBounds(0).sizes().x() + shirt().layoutBounds(1).sizes().x();
  EXPECT_GT(image.width, width * ppm);
  EXPECT_LT(image.width, (width + 0.3) * ppm);
  EXPECT_GT(image.height, 0.67 * ppm);
  // The seam colours appear in the picture: the first seam's colour is drawn on both layouts.
  const pc::Color seamColor = pv::paletteColor(0);
  int left = 0, right = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (p[0] == seamColor[0] && p[1] == seamColor[1] && p[2] == seamColor[2]) ++(x < image.width / 2 ? left : right);
    }
  }
  EXPECT_GT(left, 50);
  EXPECT_GT(right, 50);
  auto dir = pixelcloth::testing::freshDir("pictures");
  pc::writePng(dir / "pattern_tshirt.png", image);
  pc::writePng(dir / "pattern_necktie.png", pv::renderPattern(tie(), 1500));
  EXPECT_TRUE(std::filesystem::exists(dir / "pattern_necktie.png"));
  EXPECT_THROW(pv::renderPattern(shirt(), 0), pc::InputError);
}

TEST(Text, DigitsAndLettersAreDrawnWithinTheirExtent) {
  pixelcloth::core::RgbImage image(64, 32);
  const Eigen::Vector2i extent = pixelcloth::viz::textExtent("a_1", 2);
  EXPECT_EQ(extent, Eigen::Vector2i(34, 14));  // 3 glyphs of 5 columns with 1 between, 7 rows, doubled
  pixelcloth::viz::drawText(image, {3, 4}, "a_1", {0, 0, 0}, 2);
  int inside = 0, outside = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool ink = image.at(x, y)[0] == 0;
      const bool within = x >= 3 && x < 3 + extent.x() && y >= 4 && y < 4 + extent.y();
      (within ? inside : outside) += ink;
    }
  }
  EXPECT_GT(inside, 40);
  EXPECT_EQ(outside, 0);
  // '_' is the bottom row of its cell; '1' has its serif foot on the bottom row too.
  EXPECT_EQ(image.at(3 + 12 + 1, 4 + 13)[0], 0);
  EXPECT_EQ(image.at(3 + 12 + 1, 4 + 5)[0], 255);
  // Unknown characters leave a blank; clipping at the border does not throw.
  pixelcloth::core::RgbImage blank(16, 16);
  pixelcloth::viz::drawText(blank, {0, 0}, "#", {0, 0, 0}, 1);
  pixelcloth::viz::drawText(blank, {12, 12}, "88", {0, 0, 0}, 3);
  EXPECT_EQ(blank.at(0, 0)[0], 255);
  EXPECT_THROW(pixelcloth::viz::drawText(blank, {0, 0}, "1", {0, 0, 0}, 0), pixelcloth::core::InputError);
  // Punctuation of axis labels and legends has glyphs: each of these leaves ink in its own cell.
  const std::string punctuation = ",:()/%+=";
  pixelcloth::core::RgbImage marks(6 * static_cast<int>(punctuation.size()), 7);
  pixelcloth::viz::drawText(marks, {0, 0}, punctuation, {0, 0, 0}, 1);
  for (size_t k = 0; k < punctuation.size(); ++k) {
    int ink = 0;
    for (int y = 0; y < 7; ++y)
      for (int x = 6 * static_cast<int>(k); x < 6 * static_cast<int>(k) + 5; ++x) ink += marks.at(x, y)[0] == 0;
    EXPECT_GT(ink, 2) << punctuation[k];
  }
}

TEST(BasisFigures, EveryShapeFilledBothWays) {
  pv::BasisFigureOptions options;
  options.cells = 12;
  options.pictureSize = 64;
  std::vector<pv::BasisFigure> figures = pv::basisFigures(options);
  ASSERT_EQ(figures.size(), 8u);
  for (const pv::BasisFigure& figure : figures) {
    SCOPED_TRACE(figure.name());
    ASSERT_EQ(figure.height.size(), figure.patch.uv.rows());
    Eigen::VectorXd expected =
        pv::boundaryHeights(figure.patch, figure.shape, options.side, options.amplitude);  // boundary data kept
    for (size_t j = 0; j < figure.patch.boundary.size(); ++j)
      EXPECT_EQ(figure.height(figure.patch.boundary[j]), expected(j));
    // Interior within the data's range (isotropic: maximum principle; anisotropic: small undershoot allowed).
    const double slack = figure.anisotropic ? 0.25 * options.amplitude : 1e-12;
    EXPECT_LE(figure.height.maxCoeff(), expected.maxCoeff() + slack);
    EXPECT_GE(figure.height.minCoeff(), expected.minCoeff() - slack);
    EXPECT_EQ(figure.heightMap.width, 64);
    EXPECT_EQ(figure.shaded.height, 64);
  }
  pc::RgbImage sheet = pv::basisContactSheet(figures);
  EXPECT_GT(sheet.width, 4 * 64);
  EXPECT_GT(sheet.height, 4 * 64);
  options.ratio = 0;
  EXPECT_THROW(pv::basisFigures(options), pc::InputError);
}

TEST(GarmentPatches, PictureShowsBothSides) {
  std::vector<pv::PictureCurve> curves;
  for (const auto& seam : shirt().seams) curves.push_back({seam.vertices, false, pixelcloth::garment::CurveKind::Seam});
  for (const auto& line : shirt().lines) curves.push_back({line.vertices, line.closed, line.kind});
  const pc::RgbImage image = pv::renderPatches(shirt(), shirtPatches(), curves, 256);
  EXPECT_GT(image.width, 2 * 256);
  EXPECT_GT(image.height, 256);
  // Patch tints are not white: most of the area inside each layout's frame centre is coloured.
  const pc::Color white = {255, 255, 255};
  int coloured = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) coloured += !std::equal(white.begin(), white.end(), image.at(x, y));
  EXPECT_GT(coloured, image.width * image.height / 4);
}

TEST(Dressing, AreaDistortionPictureShowsLessColourAfterRelaxation) {
  const pb::Body& body = pixelcloth::testing::mannequin();
  const pcg::Dressing dressing = pcg::dressGarment(body, pcg::bodyCage(body), shirt(), pcg::garmentCage(shirt()));
  const pc::RgbImage image = pv::renderAreaDistortion(shirt(), dressing, 300);
  ASSERT_GT(image.width, 200);
  ASSERT_GT(image.height, 100);
  // Saturation (max - min channel) summed over each half: the relaxed half is paler.
  double saturation[2] = {0, 0};
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      saturation[x < image.width / 2] += std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]});
    }
  }
  EXPECT_GT(saturation[1], 1.05 * saturation[0]) << "before " << saturation[1] << ", after " << saturation[0];
  EXPECT_FALSE(inputErrorOf([&] { pv::renderAreaDistortion(pg::makeNecktie(), dressing); }).empty());
}

TEST(ClothImage, PreviewShowsLayersSideBySide) {
  pp::ClothImage image = pp::ClothImager(shirt()).rasterize(smoothOffsets(shirt()));
  pc::RgbImage rgb = pv::renderClothImage(image);
  EXPECT_EQ(rgb.width, 512);
  EXPECT_EQ(rgb.height, 256);
  pc::writePng(pixelcloth::testing::freshDir("preview") / "preview.png", rgb);
  // Corner pixels are empty (white); the centre of the front is coloured.
  EXPECT_EQ(rgb.at(0, 0)[0], 255);
  EXPECT_EQ(rgb.at(0, 0)[2], 255);
  int coloured = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 512; ++x)
      coloured += !(rgb.at(x, y)[0] == 255 && rgb.at(x, y)[1] == 255 && rgb.at(x, y)[2] == 255);
  EXPECT_GT(coloured, 0.3 * 512 * 256);
}
