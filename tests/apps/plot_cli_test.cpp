// `pixelcloth plot`, run as a program: a chart PNG from a JSON table; bad tables exit 2 and leave no PNG.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "pixelcloth/core/image.h"
#include "support/cli.h"
#include "support/test_util.h"

namespace {

using pixelcloth::testing::filesUnder;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::refused;
using pixelcloth::testing::runPixelcloth;

void writeText(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

/// Pixels of `image` that are neither white nor grey (the series' colours).
int colouredPixels(const pixelcloth::core::RgbImage& image) {
  int count = 0;
  for (size_t i = 0; i < image.pixels.size(); i += 3) {
    const int r = image.pixels[i], g = image.pixels[i + 1], b = image.pixels[i + 2];
    count += std::max({r, g, b}) - std::min({r, g, b}) > 60;
  }
  return count;
}

}  // namespace

TEST(PlotCli, DrawsEverySeriesOfATable) {
  const auto dir = freshDir("plot_cli_draws");
  nlohmann::json table = {{"title", "error against shape"},
                          {"x_label", "shape"},
                          {"y_label", "cm"},
                          {"series",
                           {{{"name", "train"}, {"x", {-1, 0, 1, 2}}, {"y", {1.2, 1.0, 1.1, 1.4}}},
                            {{"name", "test"}, {"x", {-1, 0, 1, 2}}, {"y", {1.3, 1.1, 1.2, 1.6}}}}}};
  writeText(dir / "table.json", table.dump());
  const auto run = runPixelcloth({"plot", "--table", (dir / "table.json").string(), "--out", (dir / "a.png").string(),
                                  "--width", "500", "--height", "300"});
  ASSERT_EQ(run.status, 0) << run;
  const pixelcloth::core::RgbImage image = pixelcloth::core::readPng(dir / "a.png");
  EXPECT_EQ(image.width, 500);
  EXPECT_EQ(image.height, 300);
  const int two = colouredPixels(image);
  EXPECT_GT(two, 500) << "the two lines and their dots";
  // One series fewer, fewer coloured pixels: the lines are drawn from the data.
  table["series"].erase(1);
  writeText(dir / "one.json", table.dump());
  ASSERT_EQ(runPixelcloth({"plot", "--table", (dir / "one.json").string(), "--out", (dir / "b.png").string(), "--width",
                           "500", "--height", "300"})
                .status,
            0);
  EXPECT_LT(colouredPixels(pixelcloth::core::readPng(dir / "b.png")), two * 3 / 4);
}

TEST(PlotCli, BadTablesAreRefusedNamingTheFileAndLeaveNoPicture) {
  const auto dir = freshDir("plot_cli_refused");
  const auto out = (dir / "out" / "chart.png").string();
  std::filesystem::create_directories(dir / "out");
  auto plot = [&](const std::string& name, const std::string& text) {
    writeText(dir / name, text);
    return runPixelcloth({"plot", "--table", (dir / name).string(), "--out", out});
  };
  EXPECT_TRUE(refused(runPixelcloth({"plot", "--table", (dir / "missing.json").string(), "--out", out}),
                      {"missing.json"}));
  EXPECT_TRUE(refused(plot("syntax.json", "{\"series\": ["), {"syntax.json", "invalid JSON"}));
  EXPECT_TRUE(refused(plot("noseries.json", "{\"title\": \"t\"}"), {"noseries.json", "series"}));
  EXPECT_TRUE(refused(plot("empty.json", "{\"series\": []}"), {"empty.json", "1 to 12 series"}));
  EXPECT_TRUE(refused(plot("nan.json", "{\"series\": [{\"x\": [0, 1], \"y\": [1, null]}]}"),
                      {"nan.json", "series 0", "y[1] is null", "finite number"}));
  EXPECT_TRUE(refused(plot("lengths.json", "{\"series\": [{\"x\": [0, 1, 2], \"y\": [1, 2]}]}"),
                      {"lengths.json", "3 x values but 2 y values"}));
  EXPECT_TRUE(refused(plot("text.json", "{\"series\": [{\"x\": \"0 1\", \"y\": [1, 2]}]}"),
                      {"text.json", "'x' is string"}));
  writeText(dir / "good.json", "{\"series\": [{\"x\": [0, 1], \"y\": [1, 2]}]}");
  EXPECT_TRUE(refused(runPixelcloth({"plot", "--table", (dir / "good.json").string(), "--out",
                                     (dir / "out" / "chart.jpg").string()}),
                      {"chart.jpg", ".png"}));
  EXPECT_TRUE(filesUnder(dir / "out").empty()) << "nothing half-written";
}
