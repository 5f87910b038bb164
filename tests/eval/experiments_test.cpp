// The paper's experiments end to end on a tiny plan: every table's models trained and measured on real simulated
// data, the PCA sweep and GAN, a rebased body of each kind, the necktie, the refinement; then their report.
#include "pixelcloth/eval/experiments.h"

#include <gtest/gtest.h>

#include <algorithm>
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
  plan.whole.epochs = plan.patches.epochs = plan.residual.epochs = plan.ablation.epochs = 1;
  plan.necktie.epochs = 10;
  plan.patches.schedule = pixelcloth::learn::Schedule::Cosine;
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
  EXPECT_NE(results.model("whole_shape_2").testCm, results.model("whole_l1").testCm);
  // Each family trains on its own budget, and its command says so.
  EXPECT_TRUE(std::any_of(results.commands.begin(), results.commands.end(), [](const std::string& c) {
    return c.find("--model patch --loss l1 --width 0.125 --epochs 1 --schedule cosine") != std::string::npos;
  }));
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
                           "## 7. Necktie", "## 8. Learned refinement", "## Commands", "pixelcloth generate",
                           "pose-only patch decoders (sections 2, 4 and 8): width 0.125, 1 epoch, cosine schedule"})
    EXPECT_NE(md.find(text), std::string::npos) << text;
  for (const char* figure : {"error_maps_whole.png", "error_maps_patch.png", "body_shapes.png"})
    EXPECT_GT(fs::file_size(out / "figures" / figure), 1000u) << figure;

  // A second run over the same folder keeps every dataset and finished training.
  const pe::ExperimentResults again = pe::runExperiments(tinyPlan(), out);
  EXPECT_EQ(again.model("whole_l1").testCm, results.model("whole_l1").testCm);
  EXPECT_EQ(again.model("whole_l1").seconds, 0.0);

  // Data of another solver is not taken for this one's: the folder's T-shirts are refused, naming the settings.
  pe::ExperimentPlan newton = tinyPlan();
  newton.solver = pixelcloth::sim::SolverKind::Newton;
  EXPECT_NE(inputErrorOf([&] { pe::runExperiments(newton, out); }).find("made with another 'settings'"),
            std::string::npos);
  // A report of Newton data says so, and its command line carries the solver.
  pe::ExperimentResults equilibrium = results;
  equilibrium.plan.solver = pixelcloth::sim::SolverKind::Newton;
  equilibrium.scale = "full";
  const fs::path report = pixelcloth::testing::freshDir("newton_report");
  pixelcloth::viz::writeExperimentReport(equilibrium, report);
  const std::string newtonMd = pixelcloth::core::readTextFile(report / "results.md");
  EXPECT_NE(newtonMd.find("`pixelcloth experiments --scale full --solver newton`"), std::string::npos);
  EXPECT_NE(newtonMd.find("static equilibrium"), std::string::npos);
  // With friction, the report and its commands carry the coefficient; friction without Newton is refused.
  equilibrium.plan.friction = 0.3;
  pixelcloth::viz::writeExperimentReport(equilibrium, report);
  const std::string frictionMd = pixelcloth::core::readTextFile(report / "results.md");
  EXPECT_NE(frictionMd.find("`pixelcloth experiments --scale full --solver newton --friction 0.3`"), std::string::npos);
  EXPECT_NE(frictionMd.find("Coulomb friction 0.3"), std::string::npos);
  pe::ExperimentPlan frictionPd = tinyPlan();
  frictionPd.friction = 0.3;
  EXPECT_NE(inputErrorOf([&] { frictionPd.validate(); }).find("expected 0 to 2 with newton"), std::string::npos);
  EXPECT_NE(md.find("projective dynamics"), std::string::npos);
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
  plan = tinyPlan();
  plan.residual.width = 0;
  EXPECT_NE(inputErrorOf([&] { plan.validate(); }).find("residual decoders width 0"), std::string::npos);
  plan = tinyPlan();
  plan.necktie.epochs = 0;
  EXPECT_NE(inputErrorOf([&] { plan.validate(); }).find("necktie epochs 0"), std::string::npos);
  const pe::ExperimentPlan full = pe::ExperimentPlan::ofScale(pe::Scale::Full);
  EXPECT_EQ(full.bodies.size(), 8u);
  EXPECT_NO_THROW(full.validate());
}
