// The paper's experiments end to end on a tiny plan: every table's models trained and measured on real simulated
// data, the PCA sweep and GAN, a rebased body of each kind, the necktie, the refinement; then their report.
#include "pixelcloth/eval/experiments.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/viz/experiments_report.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
namespace pe = pixelcloth::eval;
using pixelcloth::testing::inputErrorOf;

namespace {

pe::ExperimentPlan tinyPlan() {
  pe::ExperimentPlan plan;
  plan.tshirts = 10;
  plan.neckties = 10;
  plan.epochs = 1;
  plan.fcEpochs = 2;
  plan.ganEpochs = 1;
  plan.pcaComponents = 4;
  plan.bodies = {{"shape_2", 2.0, ""}, {"weights_torso", 0.0, "torso"}};
  return plan;
}

}  // namespace

TEST(Experiments, ATinyPlanRunsEveryExperimentAndItsReportPutsThePapersFiguresBesideOurs) {
  const fs::path out = pixelcloth::testing::freshDir("run");
  const pe::ExperimentResults results = pe::runExperiments(tinyPlan(), out);
  EXPECT_EQ(results.tshirt.samples, 10);
  EXPECT_EQ(results.necktie.samples, 10);
  EXPECT_GE(results.tshirt.simulated, results.tshirt.accepted);
  for (const char* name : {"whole_l1", "whole_l2", "whole_l2n", "patch_l1", "whole_default", "fc_local", "fcpca_local",
                           "fc_root", "fcpca_root", "fc_positions", "fcpca_positions", "whole_shape_2",
                           "whole_weights_torso", "necktie", "residual_clean", "residual_noisy"}) {
    SCOPED_TRACE(name);
    const pe::ModelFigures& m = results.model(name);
    EXPECT_TRUE(std::isfinite(m.trainCm) && m.trainCm > 0);
    EXPECT_TRUE(std::isfinite(m.testCm) && m.testCm > 0);
    EXPECT_TRUE(std::isfinite(m.testNormal));
    EXPECT_TRUE(fs::is_directory(m.folder));
  }
  // The rebased shirts are the same samples on another body: other errors, the same count.
  EXPECT_NE(results.model("whole_shape_2").testCm, results.model("whole_default").testCm);
  // Mean, pca:1 ... pca:rank, gan; k chosen among the pca modes.
  ASSERT_GE(results.stitchSweep.size(), 4u);
  EXPECT_EQ(results.stitchSweep.front().mode.kind, pixelcloth::stitch::StitchKind::Mean);
  EXPECT_EQ(results.stitchSweep.back().mode.kind, pixelcloth::stitch::StitchKind::Gan);
  EXPECT_GE(results.pcaK, 1);
  EXPECT_LE(results.pcaK, results.pcaRank);
  ASSERT_EQ(results.refinement.size(), 2u);
  for (const pe::RefinementFigures& f : results.refinement) {
    EXPECT_TRUE(std::isfinite(f.markersAloneCm));
    ASSERT_EQ(f.residual.test.size(), 2u);
    EXPECT_EQ(f.residual.test[1].mode.components, results.pcaK);
  }
  EXPECT_GT(results.refinement[1].markersAloneCm, results.refinement[0].markersAloneCm);  // noise costs accuracy
  EXPECT_FALSE(results.commands.empty());
  EXPECT_EQ(results.stepSeconds.size(), 8u);
  EXPECT_THROW(results.model("no such model"), pixelcloth::core::InputError);

  pixelcloth::viz::writeExperimentReport(results, out);
  const std::string md = pixelcloth::core::readTextFile(out / "results.md");
  for (const char* text : {"## 1. Loss", "| L1 | ", "0.44", "## 2. Whole garment", "0.46", "## 3. Fully connected",
                           "| local |", "0.55", "## 4. Stitching", "| gan |", "## 5, 6.", "weights_torso",
                           "## 7. Necktie", "## 8. Learned refinement", "## Commands", "pixelcloth generate"})
    EXPECT_NE(md.find(text), std::string::npos) << text;
  for (const char* figure : {"error_maps_whole.png", "error_maps_patch.png", "body_shapes.png"})
    EXPECT_GT(fs::file_size(out / "figures" / figure), 1000u) << figure;

  // A second run over the same folder keeps every dataset and finished training.
  const pe::ExperimentResults again = pe::runExperiments(tinyPlan(), out);
  EXPECT_EQ(again.model("whole_l1").testCm, results.model("whole_l1").testCm);
  EXPECT_EQ(again.model("whole_l1").seconds, 0.0);
}

TEST(Experiments, BadPlansAreRefusedNamingTheField) {
  pe::ExperimentPlan plan = tinyPlan();
  plan.tshirts = 2;
  EXPECT_NE(inputErrorOf([&] { plan.validate(); }).find("T-shirts"), std::string::npos);
  plan = tinyPlan();
  plan.bodies.push_back({"bad", 0, "legs"});
  EXPECT_NE(inputErrorOf([&] { plan.validate(); }).find("legs"), std::string::npos);
  plan = tinyPlan();
  plan.bodies.push_back({"huge", 5, ""});
  EXPECT_FALSE(inputErrorOf([&] { plan.validate(); }).empty());
  EXPECT_NE(inputErrorOf([] { pe::scaleFromName("medium", "--scale"); }).find("small or full"), std::string::npos);
  EXPECT_EQ(pe::ExperimentPlan::ofScale(pe::Scale::Full).bodies.size(), 8u);
}
