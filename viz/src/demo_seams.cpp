// The demo's seams (eval::runDemoSeams) drawn: the pose-only patch decoders' predictions stitched by the plain mean,
// feathered weights, the PCA filter at the k chosen on the regularisation split and a GAN blender, written as a seam
// report (seams/report.md) with the paper's tables on the demo's shirts.
#include <iomanip>
#include <sstream>

#include "pixelcloth/viz/demo.h"
#include "pixelcloth/viz/seam_report.h"

namespace pixelcloth::viz {

namespace {

/// "| name | train cm | test cm | normal cosine distance (test) |" of each model, and its figures under `json`.
std::string tableRows(const std::vector<eval::ModelFigures>& models, nlohmann::json& json) {
  std::ostringstream rows;
  for (const eval::ModelFigures& m : models) {
    json[m.name] = {{"train_vertex_error_cm", m.trainCm},
                    {"test_vertex_error_cm", m.testCm},
                    {"test_normal_cosine_distance", m.testNormal}};
    rows << std::fixed << std::setprecision(3) << "| " << m.name << " | " << m.trainCm << " | " << m.testCm << " | "
         << std::setprecision(4) << m.testNormal << " |\n";
  }
  return rows.str();
}

/// The paper's Tables 1 and 2 and its whole-against-patches comparison on the demo's shirts, as Markdown.
std::string paperTables(const eval::DemoSeams& seams, nlohmann::json& json) {
  std::ostringstream md;
  const std::string header = "| model | train error (cm) | test error (cm) | test normal cosine distance |\n|---|---|---|---|\n";
  md << "## The paper's tables on the demo's shirts\n\n"
     << seams.trainSamples << " train samples, " << seams.epochs
     << " epochs each; far from the paper's scale, so read the orderings, not the figures.\n\n"
     << "Table 1, the whole-garment decoder (width 0.125) by loss:\n\n"
     << header << tableRows(seams.table1, json["table1"])
     << "\nWhole garment against patches (the decoders of the Learned models section, L1 + normal):\n\n"
     << header << tableRows(seams.wholeVsPatches, json["whole_vs_patches"])
     << "\nTable 2, the fully connected baselines (2 x 256 ReLU at width 0.25, L1), direct and through "
     << seams.pcaComponents << " principal components, in the three spaces:\n\n"
     << header << tableRows(seams.table2, json["table2"]);
  return md.str();
}

}  // namespace

void demoSeams(Report& report, const body::Body& body, const eval::DemoSeams& seams) {
  const learn::TrainingData& data = seams.data;
  nlohmann::json& json = report.json()["seams"];
  const std::string tables = paperTables(seams, report.json()["paper_tables"]);
  json["gan"] = {{"width", seams.ganOptions.width},
                 {"epochs", seams.ganOptions.epochs},
                 {"best_epoch", seams.gan.bestEpoch},
                 {"seconds", seams.gan.seconds},
                 {"parameters", seams.ganParameters}};
  const std::string chosen = seams.chosen.name();
  SeamReportInputs inputs;
  inputs.title = "the demo's 28 pose-only patch decoders on its " + std::to_string(data.rows()) + " shirts, " +
                 data::splitName(seams.split) + " split (pca:K chosen on the regularisation split: " + chosen + ")";
  inputs.garment = data.garment;
  inputs.evaluations = seams.measured;
  inputs.extra = tables;
  const int row = seams.exampleRow;
  body::Body posed = body;
  posed.mesh.V = body.posedVertices(body::Pose::fromLeading(data.inputs.row(row).head(data.poseSize).transpose()));
  for (const auto& [mode, positions] : seams.examples)
    inputs.examples.push_back({"sample " + std::to_string(data.info.settings.first() + row) + ", " +
                                   (mode.kind == stitch::StitchKind::Gan ? std::string("gan") : mode.name()),
                               positions, data.truth[row].cast<double>(), posed});
  writeSeamReport(report.folder() / "seams", inputs);
  json["chosen"] = chosen;
  json["split"] = data::splitName(seams.split);
  json["modes"] = nlohmann::json::array();
  for (const stitch::Evaluation& e : seams.measured) {
    nlohmann::json m = e.metrics;
    m.erase("patches");
    m["seams"].erase("curves");
    json["modes"].push_back(m);
  }
  std::ostringstream text;
  text << std::fixed << std::setprecision(2)
       << "pixelcloth evaluate --stitch on the 28 pose-only patch decoders above, " << json["split"].get<std::string>()
       << " split. Mean per-vertex error and normal jump (|fold angle across a cage edge - ground truth's|, degrees): ";
  for (const nlohmann::json& m : json["modes"]) {
    const std::string mode = m["stitch"].get<std::string>();
    if (mode.rfind("pca:", 0) == 0 && mode != json["chosen"].get<std::string>()) continue;
    text << (mode.rfind("gan:", 0) == 0 ? std::string("GAN blender") : mode) << " "
         << m["vertex_error_cm"].get<double>() << " cm, " << m["seams"]["normal_jump_deg"].get<double>() << " deg; ";
  }
  text << "the k of the PCA filter (" << json["chosen"].get<std::string>()
       << ") was chosen on the regularisation split. The GAN blender: width " << json["gan"]["width"].get<double>()
       << ", " << json["gan"]["epochs"].get<int>() << " epochs, " << json["gan"]["seconds"].get<double>()
       << " s. The full tables, the sweep of k, a table per cage curve, and the paper's Tables 1 and 2 and its "
          "whole-against-patches comparison on these shirts are in seams/report.md. Pictures: the sweep "
          "of k; the first test sample as the mean, the PCA filter and the GAN stitch it, coloured by error, the three "
          "curves of largest normal jump marked; error maps.";
  report.section("Seams", text.str(), {"seams/pca_sweep.png", "seams/worst_seams.png", "seams/error_maps_by_mode.png"});
}

}  // namespace pixelcloth::viz
