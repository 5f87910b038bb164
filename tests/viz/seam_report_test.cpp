// What the seam report must show: the PCA sweep's two curves in their panels and colours, falling where the figures
// fall; the worst-seams picture coloured by error where the error is; report.md with a row per mode and the k of
// lowest error named.
#include "pixelcloth/viz/seam_report.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "pixelcloth/stitch/evaluate.h"
#include "pixelcloth/stitch/seams.h"
#include "pixelcloth/stitch/stitcher.h"
#include "pixelcloth/viz/draw.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
namespace pc = pixelcloth::core;
namespace ps = pixelcloth::stitch;
namespace pv = pixelcloth::viz;
using pixelcloth::testing::inputErrorOf;

namespace {

/// Number of pixels in columns [x0, x1) within `tolerance` of `color` per channel, and their mean row (-1 if none).
std::pair<int, double> pixelsNear(const pc::RgbImage& image, const pc::Color& color, int x0, int x1,
                                  int tolerance = 12) {
  int count = 0;
  double rows = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (std::abs(p[0] - color[0]) <= tolerance && std::abs(p[1] - color[1]) <= tolerance &&
          std::abs(p[2] - color[2]) <= tolerance) {
        ++count;
        rows += y;
      }
    }
  return {count, count ? rows / count : -1.0};
}

/// Yellow-ish pixels (the top of the error ramp, shaded): strong red and green, little blue.
int yellowPixels(const pc::RgbImage& image) {
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      count += p[0] > 140 && p[1] > 140 && p[2] < 90;
    }
  return count;
}

/// An evaluation of `mode` with the given figures, its seam metrics those of `positions` against `truth`.
ps::Evaluation evaluation(const std::string& mode, double errorCm, double jumpDeg, const Eigen::MatrixX3d& positions,
                          const Eigen::MatrixX3d& truth) {
  const ps::SeamLayout layout(pixelcloth::testing::tshirt());
  ps::SeamMetrics seams(layout);
  seams.add({}, positions, truth);
  ps::Evaluation e;
  e.mode = ps::parseStitchMode(mode, "test");
  nlohmann::json s = seams.toJson();
  s["normal_jump_deg"] = jumpDeg;
  e.metrics = {{"split", "test"},
               {"samples", 4},
               {"stitch", mode},
               {"vertex_error_cm", errorCm},
               {"normal_cosine_distance", 0.05},
               {"base_vertex_error_cm", nullptr},
               {"seams", s}};
  e.vertexErrorCm = Eigen::VectorXd::Constant(truth.rows(), errorCm);
  return e;
}

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST(SeamReport, PcaSweepDrawsErrorLeftAndJumpRightFallingWhereTheFiguresFall) {
  const Eigen::MatrixX3d truth = pixelcloth::testing::tshirt().mesh.V;
  // Error falls with k; the normal jump rises.
  const std::vector<ps::Evaluation> evaluations = {
      evaluation("mean", 3.5, 10, truth, truth), evaluation("pca:1", 3.0, 2, truth, truth),
      evaluation("pca:4", 2.0, 5, truth, truth), evaluation("pca:16", 1.0, 8, truth, truth)};
  const int width = 720;
  const pc::RgbImage image = pv::renderPcaSweep(evaluations, width, 300);
  ASSERT_EQ(image.width, width);
  const pc::Color blue = {40, 100, 200}, orange = {230, 120, 20};
  const int half = width / 2;
  EXPECT_GT(pixelsNear(image, blue, 0, half).first, 100);
  EXPECT_EQ(pixelsNear(image, blue, half, width).first, 0);
  EXPECT_GT(pixelsNear(image, orange, half, width).first, 100);
  EXPECT_EQ(pixelsNear(image, orange, 0, half).first, 0);
  // The error curve starts high (small row) and ends low; the jump curve the other way round.
  const double errorAtSmallK = pixelsNear(image, blue, 50, 90).second,
               errorAtLargeK = pixelsNear(image, blue, half - 50, half).second;
  const double jumpAtSmallK = pixelsNear(image, orange, half + 50, half + 90).second,
               jumpAtLargeK = pixelsNear(image, orange, width - 50, width).second;
  EXPECT_LT(errorAtSmallK, errorAtLargeK - 50);
  EXPECT_GT(jumpAtSmallK, jumpAtLargeK + 20);
}

TEST(SeamReport, PcaSweepOfFewerThanTwoModesIsRefused) {
  const Eigen::MatrixX3d truth = pixelcloth::testing::tshirt().mesh.V;
  const std::string message = inputErrorOf([&] {
    pv::renderPcaSweep({evaluation("mean", 2, 10, truth, truth), evaluation("pca:4", 1, 5, truth, truth)});
  });
  EXPECT_NE(message.find("expected two or more"), std::string::npos) << message;
}

TEST(SeamReport, WorstSeamsAreColouredByErrorWhereItIsAndMarked) {
  const pixelcloth::garment::Garment& shirt = pixelcloth::testing::tshirt();
  const Eigen::MatrixX3d truth = shirt.mesh.V;
  Eigen::MatrixX3d moved = truth;
  for (Eigen::Index v = 0; v < moved.rows(); ++v)
    if (moved(v, 0) > 0.05) moved(v, 2) += 0.05;  // one side 5 cm forward
  pv::SeamExample exact{"exact", truth, truth, pixelcloth::testing::coarseMannequin()};
  pv::SeamExample off{"off", moved, truth, pixelcloth::testing::coarseMannequin()};
  const pc::RgbImage right = pv::renderWorstSeams(shirt, exact, 5.0, 240);
  const pc::RgbImage wrong = pv::renderWorstSeams(shirt, off, 5.0, 240);
  EXPECT_LT(yellowPixels(right), 50);
  EXPECT_GT(yellowPixels(wrong), 1000);
  // The three curves of largest jump are marked in the palette's first colours, on the garment and in the legend.
  for (int r = 0; r < 3; ++r) EXPECT_GT(pixelsNear(wrong, pv::paletteColor(r), 0, wrong.width, 0).first, 20) << r;
}

TEST(SeamReport, ReportHasARowPerModeAndNamesTheKOfLowestError) {
  const pixelcloth::garment::Garment& shirt = pixelcloth::testing::tshirt();
  const Eigen::MatrixX3d truth = shirt.mesh.V;
  Eigen::MatrixX3d moved = truth;
  moved.col(1).array() += 0.01;
  pv::SeamReportInputs inputs;
  inputs.title = "a test";
  inputs.command = "pixelcloth evaluate --stitch mean,pca:1,pca:4,pca:16";
  inputs.garment = shirt;
  inputs.evaluations = {evaluation("mean", 2.0, 10, moved, truth), evaluation("pca:1", 1.9, 9, moved, truth),
                        evaluation("pca:4", 1.5, 6, moved, truth), evaluation("pca:16", 1.7, 7, moved, truth)};
  inputs.examples.push_back({"sample 0, mean", moved, truth, pixelcloth::testing::coarseMannequin()});
  const fs::path folder = pixelcloth::testing::freshDir("report");
  pv::writeSeamReport(folder, inputs);
  for (const char* file : {"report.md", "pca_sweep.png", "error_maps_by_mode.png", "worst_seams.png"})
    EXPECT_TRUE(fs::is_regular_file(folder / file)) << file;
  const std::string md = readText(folder / "report.md");
  EXPECT_NE(md.find("# Seams: a test"), std::string::npos);
  EXPECT_NE(md.find(inputs.command), std::string::npos);
  for (const char* row : {"| mean | 2.000 |", "| pca:1 | 1.900 |", "| pca:4 | 1.500 |", "| pca:16 | 1.700 |"})
    EXPECT_NE(md.find(row), std::string::npos) << row << "\n" << md;
  EXPECT_NE(md.find("Lowest vertex error at pca:4: 1.500 cm (-25.0% against the plain mean), normal jump 6.00 deg "
                    "(-40.0%)"),
            std::string::npos)
      << md;
  // The per-curve table compares the mean with that k, a row per cage curve of the garment.
  EXPECT_NE(md.find("normal jump, mean (deg) | normal jump, pca:4 (deg)"), std::string::npos);
  EXPECT_NE(md.find("| side_left | seam |"), std::string::npos);
}
