// What the charts and value maps must show: each series or value where it belongs, in its colour.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>

#include "pixelcloth/core/error.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/line_chart.h"
#include "pixelcloth/viz/patch_picture.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;
namespace pv = pixelcloth::viz;
using pixelcloth::testing::inputErrorOf;

namespace {

/// Pixels of `image` for which `match` holds, and the mean row of those pixels (-1 when none).
std::pair<int, double> pixelsWhere(const pc::RgbImage& image, const std::function<bool(const pc::Color&)>& match) {
  int count = 0;
  double rows = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (match({p[0], p[1], p[2]})) {
        ++count;
        rows += y;
      }
    }
  return {count, count ? rows / count : -1.0};
}

std::function<bool(const pc::Color&)> exactly(const pc::Color& color) {
  return [color](const pc::Color& c) { return c == color; };
}

}  // namespace

TEST(LineChart, EachSeriesIsDrawnInItsPaletteColourAndTheHigherOneAbove) {
  pv::LineChart chart;
  chart.title = "two series";
  chart.series = {{"low", {0, 1, 2, 3}, {1, 1.2, 1.1, 1.3}}, {"high", {0, 1, 2, 3}, {5, 5.5, 5.2, 5.8}}};
  const pc::RgbImage image = pv::renderLineChart(chart, 640, 400);
  EXPECT_EQ(image.width, 640);
  EXPECT_EQ(image.height, 400);
  const auto [lowPixels, lowRow] = pixelsWhere(image, exactly(pv::paletteColor(0)));
  const auto [highPixels, highRow] = pixelsWhere(image, exactly(pv::paletteColor(1)));
  EXPECT_GT(lowPixels, 100);
  EXPECT_GT(highPixels, 100);
  EXPECT_LT(highRow, lowRow);  // larger values are drawn higher up
}

TEST(LineChart, BadTablesAreRefusedNamingTheFile) {
  const nlohmann::json good = {{"title", "t"},
                               {"x_label", "x"},
                               {"y_label", "y"},
                               {"series", {{{"name", "a"}, {"x", {0, 1}}, {"y", {2, 3}}}}}};
  EXPECT_NO_THROW(pv::lineChartFromJson(good, "t.json"));
  nlohmann::json uneven = good;
  uneven["series"][0]["y"] = {2};
  EXPECT_NE(inputErrorOf([&] { pv::lineChartFromJson(uneven, "t.json"); }).find("t.json"), std::string::npos);
  nlohmann::json notANumber = good;
  notANumber["series"][0]["y"][1] = "three";
  EXPECT_NE(inputErrorOf([&] { pv::lineChartFromJson(notANumber, "t.json"); }).find("t.json"), std::string::npos);
  nlohmann::json missing = good;
  missing.erase("series");
  EXPECT_NE(inputErrorOf([&] { pv::lineChartFromJson(missing, "t.json"); }).find("series"), std::string::npos);
}

TEST(PatternValues, HighValuesAreRedAndLowOnesBlueWhereTheyLie) {
  const pg::Garment& shirt = pixelcloth::testing::tshirt();
  const int V = shirt.mesh.numVertices();
  auto reddish = [](const pc::Color& c) { return c[0] > c[2] + 80; };
  auto bluish = [](const pc::Color& c) { return c[2] > c[0] + 80; };
  // Zero everywhere: no red.
  const pc::RgbImage zero = pv::renderPatternValues(shirt, Eigen::VectorXd::Zero(V), 1.0, "zero", 256, true);
  EXPECT_EQ(pixelsWhere(zero, reddish).first, 0);
  EXPECT_GT(pixelsWhere(zero, bluish).first, 1000);
  // The full value on the upper half of the shirt, zero below: red above blue in the pattern too.
  Eigen::VectorXd values(V);
  for (int v = 0; v < V; ++v) values(v) = shirt.mesh.V(v, 1) > shirt.mesh.V.col(1).mean() ? 1.0 : 0.0;
  const pc::RgbImage split = pv::renderPatternValues(shirt, values, 1.0, "split", 256, true);
  const auto [red, redRow] = pixelsWhere(split, reddish);
  const auto [blue, blueRow] = pixelsWhere(split, bluish);
  EXPECT_GT(red, 500);
  EXPECT_GT(blue, 500);
  EXPECT_LT(redRow, blueRow);
}

TEST(ContactSheet, PicturesAreLaidOutInEqualCellsWithGaps) {
  const pc::RgbImage a(30, 20, {0, 0, 0}), b(50, 10, {200, 0, 0});
  const pc::RgbImage sheet = pv::contactSheet({a, b, a}, 2, 8);
  // Cells as large as the largest picture (50 x 20), a gap around and between them.
  EXPECT_EQ(sheet.width, 2 * 50 + 3 * 8);
  EXPECT_EQ(sheet.height, 2 * 20 + 3 * 8);
  EXPECT_EQ(pc::Color({sheet.at(8, 8)[0], sheet.at(8, 8)[1], sheet.at(8, 8)[2]}), pc::Color({0, 0, 0}));
  EXPECT_EQ(sheet.at(8 + 50 + 8, 8)[0], 200);       // b, first row, second column
  EXPECT_EQ(sheet.at(8, 8 + 20 + 8)[0], 0);         // the third picture, second row
  EXPECT_EQ(sheet.at(8 + 50 + 8, 8 + 20 + 8)[0], 255);  // no fourth picture: background
}

TEST(PatchPicture, EachCurveKindHasItsOwnColour) {
  const pg::Garment& shirt = pixelcloth::testing::tshirt();
  const std::vector<pixelcloth::patches::Patch> patches = pixelcloth::patches::garmentPatches(shirt);
  std::vector<pv::PictureCurve> loops;
  for (const auto& line : shirt.lines)
    if (line.kind == pg::CurveKind::Loop) loops.push_back({line.vertices, line.closed, line.kind});
  ASSERT_FALSE(loops.empty());
  const pc::RgbImage withLoops = pv::renderPatches(shirt, patches, loops, 256);
  const pc::Color loopBlue = {20, 70, 200}, seamRed = {170, 20, 30};
  EXPECT_GT(pixelsWhere(withLoops, exactly(loopBlue)).first, 50);
  EXPECT_EQ(pixelsWhere(withLoops, exactly(seamRed)).first, 0);
  std::vector<pv::PictureCurve> seams;
  for (const auto& seam : shirt.seams) seams.push_back({seam.vertices, false, pg::CurveKind::Seam});
  const pc::RgbImage withSeams = pv::renderPatches(shirt, patches, seams, 256);
  EXPECT_GT(pixelsWhere(withSeams, exactly(seamRed)).first, 50);
  EXPECT_EQ(pixelsWhere(withSeams, exactly(loopBlue)).first, 0);
}

TEST(TrainingCurves, BothSplitsAreDrawn) {
  pixelcloth::learn::NetworkReport report;
  for (int e = 1; e <= 6; ++e) {
    pixelcloth::learn::EpochRecord r;
    r.epoch = e;
    r.trainErrorCm = 4.0 / e;
    r.regularisationErrorCm = 5.0 / e + 0.2;
    r.seconds = 10;
    report.epochs.push_back(r);
  }
  report.bestEpoch = 6;
  const pc::RgbImage image = pv::renderTrainingCurves(report, "whole");
  auto bluish = [](const pc::Color& c) { return c[2] > c[0] + 80 && c[2] > 120; };
  auto orange = [](const pc::Color& c) { return c[0] > 200 && c[1] > 80 && c[1] < 180 && c[2] < 80; };
  // Both splits in both panels: against the epoch (left half) and against wall time (right half).
  auto inHalf = [&](bool right, const std::function<bool(const pc::Color&)>& colour) {
    int count = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = right ? image.width / 2 : 0; x < (right ? image.width : image.width / 2); ++x) {
        const std::uint8_t* p = image.at(x, y);
        count += colour({p[0], p[1], p[2]}) ? 1 : 0;
      }
    return count;
  };
  for (bool right : {false, true}) {
    EXPECT_GT(inHalf(right, bluish), 50) << (right ? "wall time" : "epoch");
    EXPECT_GT(inHalf(right, orange), 50) << (right ? "wall time" : "epoch");
  }
}

TEST(TrainingCurves, TheWallTimePanelSpacesEpochsByTheirSeconds) {
  // Five epochs of 1 s at 4 cm, then one of 100 s ending at 1 cm. Against the epoch the drop is the last fifth of the
  // panel, so the curve is still at 4 cm half way across; against wall time the drop takes nearly the whole panel, so
  // half way across the curve is already well below.
  pixelcloth::learn::NetworkReport report;
  for (int e = 1; e <= 6; ++e) {
    pixelcloth::learn::EpochRecord r;
    r.epoch = e;
    r.trainErrorCm = e == 6 ? 1.0 : 4.0;
    r.regularisationErrorCm = std::nan("");
    r.seconds = e == 6 ? 100 : 1;
    report.epochs.push_back(r);
  }
  report.bestEpoch = 6;
  const pc::RgbImage image = pv::renderTrainingCurves(report, "a slow last epoch");
  auto blueRow = [&](int x) {  // mean row of the blue curve's pixels in column x (-1: none)
    double rows = 0;
    int count = 0;
    for (int y = 0; y < image.height; ++y) {
      const std::uint8_t* p = image.at(x, y);
      if (p[2] > p[0] + 80 && p[2] > 120) rows += y, ++count;
    }
    return count > 0 ? rows / count : -1.0;
  };
  const double epochMiddle = blueRow(image.width / 4), wallMiddle = blueRow(3 * image.width / 4);
  ASSERT_GT(epochMiddle, 0);
  ASSERT_GT(wallMiddle, 0);
  EXPECT_GT(wallMiddle, epochMiddle + 40) << "rows grow downwards: lower errors sit lower";
}
