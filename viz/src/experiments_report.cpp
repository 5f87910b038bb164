#include "pixelcloth/viz/experiments_report.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/eval/paper_figures.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/viz/line_chart.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"

namespace pixelcloth::viz {

namespace fs = std::filesystem;

namespace {

/// "width 0.5, 20 epochs, cosine schedule".
std::string budget(const eval::CnnBudget& b) {
  std::ostringstream out;
  out << "width " << b.width << ", " << b.epochs << (b.epochs == 1 ? " epoch, " : " epochs, ")
      << learn::scheduleName(b.schedule) << " schedule";
  return out.str();
}

std::string cm(double value, int digits = 3) {
  if (!std::isfinite(value)) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

/// "yes" when ours is ordered as the paper's (a below b), else "no".
const char* agrees(double a, double b) { return a < b ? "yes" : "no"; }

/// json[key] when it is a number, else NaN (a figure that does not apply is null).
double number(const nlohmann::json& json, const char* key) {
  return json.is_object() && json.contains(key) && json[key].is_number() ? json[key].get<double>() : std::nan("");
}

double metric(const stitch::Evaluation& e, const char* key) { return number(e.metrics, key); }

/// The test split's per-vertex errors of `model` (its plain mean), on the pattern, 0 to `maxCm`.
core::RgbImage errorMaps(const eval::ModelFigures& model, const garment::Garment& garment, double maxCm) {
  const stitch::Evaluation& test = model.test.front();
  std::ostringstream title;
  title << model.name << ", test split: mean vertex error " << cm(metric(test, "vertex_error_cm")) << " cm (0 to "
        << cm(maxCm, 2) << " cm)";
  return renderPatternValues(garment, test.vertexErrorCm, maxCm, title.str(), 384, true);
}

}  // namespace

void writeExperimentReport(const eval::ExperimentResults& r, const fs::path& out) {
  namespace paper = eval::paper;
  const fs::path figures = out / "figures";
  fs::create_directories(figures);
  const garment::Garment shirt = data::datasetGarment(data::readDatasetInfo(r.tshirt.folder));
  const eval::ModelFigures &whole = r.model("whole_default"), &patch = r.model("patch_l1");
  // One colour scale for both, 0 to 1 cm or to the worse model's 95th percentile when that is higher.
  const double maxCm =
      std::max({1.0, whole.test.front().vertexErrorQuantileCm(0.95), patch.test.front().vertexErrorQuantileCm(0.95)});
  core::writePng(figures / "error_maps_whole.png", errorMaps(whole, shirt, maxCm));
  core::writePng(figures / "error_maps_patch.png", errorMaps(patch, shirt, maxCm));

  // Error against the body shape: the shape variants and the body simulated on (0: Table 1's L1 row, trained alike).
  const eval::ModelFigures& reference = r.model("whole_l1");
  LineChart chart;
  chart.title = "error against body shape";
  chart.xLabel = "shape parameter (0: simulated on)";
  chart.yLabel = "whole CNN, L1: per-vertex error in cm";
  std::vector<std::pair<double, const eval::ModelFigures*>> shapes = {{0.0, &reference}};
  for (const eval::BodyVariant& body : r.plan.bodies)
    if (body.corruptWeights.empty()) shapes.emplace_back(body.shape, &r.model("whole_" + body.name));
  std::sort(shapes.begin(), shapes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  ChartSeries train{"train", {}, {}}, test{"test", {}, {}};
  for (const auto& [shape, model] : shapes) {
    train.x.push_back(shape);
    train.y.push_back(model->trainCm);
    test.x.push_back(shape);
    test.y.push_back(model->testCm);
  }
  chart.series = {train, test};
  core::writePng(figures / "body_shapes.png", renderLineChart(chart));

  const eval::ExperimentPlan& p = r.plan;
  const bool newton = p.solver == sim::SolverKind::Newton;
  const std::string solverFlag = eval::simulatorFlags(p);
  std::ostringstream friction;
  if (p.friction > 0) friction << ", Coulomb friction " << p.friction;
  const std::string simulatedBy =
      newton ? "Both datasets simulated to static equilibrium (Newton" + friction.str() + ", docs/simulation.md)."
             : "Both datasets simulated by projective dynamics' fixed schedule.";
  std::ostringstream md;
  md << "# The paper's experiments on pixelcloth's data (" << r.scale << " scale)\n\n"
     << "Made by "
     << (r.scale == "custom" ? std::string("a custom plan of eval::runExperiments")
                             : "`pixelcloth experiments --scale " + r.scale + solverFlag + "`")
     << " in " << cm(r.seconds, 0) << " s. " << simulatedBy << " T-shirts: " << r.tshirt.samples << " samples ("
     << r.tshirt.accepted << " accepted of " << r.tshirt.simulated << " simulated poses; " << r.tshirt.train
     << " train, " << r.tshirt.regularisation << " regularisation, " << r.tshirt.test
     << " test). Neckties: " << r.necktie.samples << " (" << r.necktie.train << " train, " << r.necktie.test
     << " test).\n\n"
     << "- whole-garment decoder (sections 2 and 3): " << budget(p.whole) << "\n"
     << "- pose-only patch decoders (sections 2, 4 and 8): " << budget(p.patches) << "\n"
     << "- residual patch decoders (section 8): " << budget(p.residual) << "\n"
     << "- losses and bodies (sections 1, 5 and 6, whole decoder): " << budget(p.ablation) << "\n"
     << "- necktie (section 7): " << budget(p.necktie) << ", batch 4\n"
     << "- fully connected baselines: " << p.fcEpochs << " epochs; GAN blender: " << p.ganEpochs << " epochs\n\n"
     << "Errors are mean per-vertex distances in cm, \"normal\" the mean normal cosine distance, each on the split "
        "named; models were selected on the regularisation split. The paper's figures (its PhysBAM data: 16K train "
        "samples, networks of width 1) stand beside ours; read the orderings, not the figures.\n\n";
  if (r.scale == "small")
    md << "**A smoke run**: datasets of this size say nothing about the orderings; the full scale is what counts.\n\n";

  md << "## 1. Loss (the paper's Table 1)\n\n"
     << "| loss | train cm | test cm | train normal | test normal | paper: train cm | test cm | train normal | test "
        "normal |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  const char* table1[] = {"whole_l1", "whole_l2", "whole_l2n"};
  for (int i = 0; i < 3; ++i) {
    const eval::ModelFigures& m = r.model(table1[i]);
    const paper::Row& q = paper::kTable1[i];
    md << "| " << q.label << " | " << cm(m.trainCm) << " | " << cm(m.testCm) << " | " << cm(m.trainNormal, 4) << " | "
       << cm(m.testNormal, 4) << " | " << q.trainCm << " | " << q.testCm << " | " << q.trainNormal << " | "
       << q.testNormal << " |\n";
  }
  md << "\nL1 below L2 on test vertex error (the paper's ordering): "
     << agrees(r.model("whole_l1").testCm, r.model("whole_l2").testCm)
     << ". L2 + normal below L2 on train normal distance: "
     << agrees(r.model("whole_l2n").trainNormal, r.model("whole_l2").trainNormal) << ".\n\n";

  md << "## 2. Whole garment against 28 patches (L1, the garment's normal weight)\n\n"
     << "| model | train cm | test cm | paper: train cm | test cm |\n|---|---:|---:|---:|---:|\n"
     << "| whole | " << cm(whole.trainCm) << " | " << cm(whole.testCm) << " | "
     << paper::kWholeAgainstPatches[0].trainCm << " | " << paper::kWholeAgainstPatches[0].testCm << " |\n"
     << "| patches | " << cm(patch.trainCm) << " | " << cm(patch.testCm) << " | "
     << paper::kWholeAgainstPatches[1].trainCm << " | " << paper::kWholeAgainstPatches[1].testCm << " |\n\n"
     << "Patches below whole on test: " << agrees(patch.testCm, whole.testCm)
     << ". Test error maps: [whole](figures/error_maps_whole.png), [patches](figures/error_maps_patch.png).\n\n";

  md << "## 3. Fully connected, direct and through principal components (the paper's Table 2)\n\n"
     << "| space | fc train | fc test | fc-pca train | fc-pca test | paper: fc train | fc test | fc-pca train | "
        "fc-pca test |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const paper::FullyConnectedRow& q : paper::kTable2) {
    const eval::ModelFigures &fc = r.model(std::string("fc_") + q.space),
                             &fcpca = r.model(std::string("fcpca_") + q.space);
    md << "| " << q.space << " | " << cm(fc.trainCm) << " | " << cm(fc.testCm) << " | " << cm(fcpca.trainCm) << " | "
       << cm(fcpca.testCm) << " | " << q.directTrainCm << " | " << q.directTestCm << " | " << q.pcaTrainCm << " | "
       << q.pcaTestCm << " |\n";
  }
  md << "\nfc-pca below fc on test in the local space: "
     << agrees(r.model("fcpca_local").testCm, r.model("fc_local").testCm)
     << ". The patch decoders below fc-pca (local) on test: " << agrees(patch.testCm, r.model("fcpca_local").testCm)
     << "; the whole decoder: " << agrees(whole.testCm, r.model("fcpca_local").testCm)
     << ". Both below every fully connected network on test, as in the paper: "
     << agrees(
            std::max(whole.testCm, patch.testCm),
            std::min({r.model("fc_local").testCm, r.model("fcpca_local").testCm, r.model("fc_root").testCm,
                      r.model("fcpca_root").testCm, r.model("fc_positions").testCm, r.model("fcpca_positions").testCm}))
     << ".\n\n";

  md << "## 4. Stitching the patch decoders' test predictions: the PCA filter of k components, and the GAN\n\n"
     << "| stitch | test cm | normal jump deg | gap cm |\n|---|---:|---:|---:|\n";
  for (const stitch::Evaluation& e : r.stitchSweep) {
    const std::string name = e.mode.kind == stitch::StitchKind::Gan ? std::string("gan") : e.mode.name();
    const nlohmann::json seams = e.metrics.value("seams", nlohmann::json::object());
    md << "| " << name << " | " << cm(metric(e, "vertex_error_cm")) << " | " << cm(number(seams, "normal_jump_deg"), 2)
       << " | " << cm(number(seams.value("gap_cm", nlohmann::json::object()), "mean")) << " |\n";
  }
  md << "\nPCA rank " << r.pcaRank << " (the train split's); k = " << r.pcaK
     << " is the best on the regularisation split. The paper kept " << paper::kBestPcaComponents
     << " components of its 16K samples.\n\n";

  md << "## 5, 6. Wrong body shapes and broken skinning (whole CNN, L1; the same shirts rebased)\n\n"
     << "| body | train cm | test cm |\n|---|---:|---:|\n"
     << "| shape 0 (simulated on; Table 1's L1 row) | " << cm(reference.trainCm) << " | " << cm(reference.testCm)
     << " |\n";
  double worstShape = 0, worstWeights = 0;
  for (const eval::BodyVariant& body : p.bodies) {
    const eval::ModelFigures& m = r.model("whole_" + body.name);
    md << "| " << body.name << " | " << cm(m.trainCm) << " | " << cm(m.testCm) << " |\n";
    (body.corruptWeights.empty() ? worstShape : worstWeights) =
        std::max(body.corruptWeights.empty() ? worstShape : worstWeights, m.testCm);
  }
  md << "\n![error against body shape](figures/body_shapes.png)\n\n"
     << "The paper: the error stays roughly constant. Here the largest test error over the body shapes is "
     << cm(worstShape) << " cm, over the broken skinnings " << cm(worstWeights) << " cm, against "
     << cm(reference.testCm) << " cm on the body simulated on.\n\n";

  const eval::ModelFigures& tie = r.model("necktie");
  md << "## 7. Necktie (36 pose floats, root-frame offsets, edge loss)\n\n"
     << "| model | train cm | test cm |\n|---|---:|---:|\n| necktie CNN | " << cm(tie.trainCm) << " | "
     << cm(tie.testCm) << " |\n\n";

  md << "## 8. Learned refinement of the marker reconstruction (patch decoders)\n\n"
     << "| method |";
  for (const eval::RefinementFigures& f : r.refinement) md << " test cm, " << cm(f.noiseCm, 1) << " cm noise |";
  md << "\n|---|";
  for (size_t i = 0; i < r.refinement.size(); ++i) md << "---:|";
  md << "\n| markers alone (spline + anisotropic fill) |";
  for (const eval::RefinementFigures& f : r.refinement) md << " " << cm(f.markersAloneCm) << " |";
  md << "\n| pose-only patches |";
  for (size_t i = 0; i < r.refinement.size(); ++i) md << " " << cm(patch.testCm) << " |";
  md << "\n| residual patches |";
  for (const eval::RefinementFigures& f : r.refinement) md << " " << cm(f.residual.testCm) << " |";
  md << "\n| residual patches + PCA (k = " << r.pcaK << ") |";
  for (const eval::RefinementFigures& f : r.refinement)
    md << " " << cm(f.residual.test.size() > 1 ? metric(f.residual.test[1], "vertex_error_cm") : std::nan("")) << " |";
  if (!r.refinement.empty())
    md << "\n\nResidual below pose-only on test (clean markers): "
       << agrees(r.refinement.front().residual.testCm, patch.testCm) << ".";
  md << "\n\n## Wall time per step\n\n";
  for (const auto& [step, seconds] : r.stepSeconds) md << "- " << step << ": " << cm(seconds, 0) << " s\n";
  md << "\n## Training times\n\n| model | s |\n|---|---:|\n";
  for (const auto& [name, m] : r.models) md << "| " << name << " | " << cm(m.seconds, 0) << " |\n";
  md << "\n(0: a finished run was kept.)\n\n## Commands\n\nThe same steps through the command line:\n\n```\n";
  for (const std::string& c : r.commands) md << c << "\n";
  md << "```\n";
  core::writeTextAtomically(out / "results.md", md.str());
}

}  // namespace pixelcloth::viz
