// `pixelcloth model --summary`, run as a program: the sizes it prints are the library's, bad options exit 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/cli.h"

namespace {

using pixelcloth::testing::CliRun;
using pixelcloth::testing::refused;
using pixelcloth::testing::runPixelcloth;

nlohmann::json summaryOf(std::initializer_list<std::string> args) {
  const CliRun run = runPixelcloth(args);
  EXPECT_EQ(run.status, 0) << run;
  return nlohmann::json::parse(run.out);
}

}  // namespace

TEST(ModelCli, SummaryPrintsParametersShapesAndCost) {
  const nlohmann::json patch = summaryOf({"model", "--arch", "patch", "--summary"});
  EXPECT_EQ(patch["parameters"], 3961219);
  EXPECT_EQ(patch["input"], nlohmann::json::array({90}));
  EXPECT_EQ(patch["output"], nlohmann::json::array({3, 160, 160}));
  EXPECT_GT(patch["gflop_forward"].get<double>(), 0.1);
  const nlohmann::json quarter = summaryOf({"model", "--arch", "whole", "--width", "0.25", "--summary"});
  EXPECT_LT(quarter["parameters"].get<double>(), 1e6);
  EXPECT_EQ(quarter["output"], nlohmann::json::array({6, 256, 256}));
  // The baselines predict 3 values per vertex of the garment.
  const nlohmann::json fc = summaryOf({"model", "--arch", "fc", "--garment", "necktie", "--summary"});
  EXPECT_EQ(fc["output"][0].get<int>() % 3, 0);
  EXPECT_GT(fc["output"][0].get<int>(), 3 * 400);
  const nlohmann::json pca = summaryOf({"model", "--arch", "fc-pca", "--values", "300", "--summary"});
  EXPECT_EQ(pca["output"], nlohmann::json::array({300}));
}

TEST(ModelCli, BadOptionsAreRefused) {
  EXPECT_TRUE(refused(runPixelcloth({"model", "--arch", "patch", "--width", "0", "--summary"}), {"width"}));
  EXPECT_TRUE(refused(runPixelcloth({"model", "--arch", "cnn", "--summary"}), {"--arch"}));
  EXPECT_TRUE(refused(runPixelcloth({"model", "--arch", "patch"}), {"--summary"}));
  EXPECT_TRUE(refused(runPixelcloth({"model", "--arch", "fc-pca", "--values", "10", "--summary"}), {"PCA components"}));
}
