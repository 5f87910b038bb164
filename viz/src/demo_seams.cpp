// The demo's seams: the pose-only patch decoders' predictions stitched by the plain mean, feathered weights, the PCA
// filter at the k chosen on the regularisation split, and a GAN blender trained here; measured on the test split and
// written as a seam report (seams/report.md).
#include <iomanip>
#include <sstream>

#include "pixelcloth/data/dataset.h"
#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/training_data.h"
#include "pixelcloth/stitch/evaluate.h"
#include "pixelcloth/stitch/gan.h"
#include "pixelcloth/stitch/pca_filter.h"
#include "pixelcloth/stitch/stitcher.h"
#include "pixelcloth/viz/demo.h"
#include "pixelcloth/viz/seam_report.h"

namespace pixelcloth::viz {

namespace fs = std::filesystem;

void demoSeams(Report& report, const body::Body& body) {
  const fs::path datasetFolder = report.folder() / "dataset_tshirt", patchFolder = report.folder() / "model_patch",
                 ganFolder = report.folder() / "model_gan";
  const garment::Garment shirt = data::datasetGarment(data::readDatasetInfo(datasetFolder));
  const learn::TrainedModel model(patchFolder, shirt);
  const learn::TrainingData data = learn::loadTrainingData(datasetFolder, model.space(), fs::path());
  nlohmann::json& json = report.json()["seams"];
  report.step("seams: a GAN blender of the patch decoders' stitched predictions", [&] {
    stitch::GanOptions options;
    options.width = 0.0625;
    options.epochs = 3;
    options.quiet = true;
    const stitch::GanReport gan = stitch::trainGan(model, data, options, ganFolder);
    json["gan"] = {{"width", options.width}, {"epochs", options.epochs}, {"best_epoch", gan.bestEpoch},
                   {"seconds", gan.seconds}, {"parameters", stitch::ganSummary(options.width)["generator"]["parameters"]}};
  });
  report.step("seams: every stitch mode, k chosen on the regularisation split, measured on the test split", [&] {
    auto pca = std::make_shared<stitch::PcaFilter>(stitch::PcaFilter::fit(data));
    pca->save(stitch::defaultPcaFolder(patchFolder));
    std::vector<stitch::Stitcher> sweep;
    sweep.emplace_back(shirt, stitch::parseStitchMode("mean", "demo"));
    for (int k = 1; k < pca->rank(); k *= 2) sweep.emplace_back(shirt, stitch::parseStitchMode("pca:" + std::to_string(k), "demo"), pca);
    sweep.emplace_back(shirt, stitch::parseStitchMode("pca:" + std::to_string(pca->rank()), "demo"), pca);
    std::vector<const stitch::Stitcher*> modes;
    for (const stitch::Stitcher& s : sweep) modes.push_back(&s);
    const std::vector<stitch::Evaluation> chosenOn = stitch::evaluate(model, data, "regularisation", modes);
    const int best = bestPcaMode(chosenOn);
    const std::string chosen = chosenOn[best].metrics["stitch"].get<std::string>();

    std::vector<stitch::Stitcher> final;
    for (const std::string& mode : {std::string("mean"), std::string("feather"), chosen, "gan:" + ganFolder.string()})
      final.emplace_back(shirt, stitch::parseStitchMode(mode, "demo"), pca);
    // The test split with the sweep too, so the report's plot shows it; the chosen k is the regularisation split's.
    for (const stitch::Stitcher& s : sweep)
      if (s.mode().kind == stitch::StitchKind::Pca && s.mode().name() != chosen)
        final.emplace_back(shirt, s.mode(), pca);
    modes.clear();
    for (const stitch::Stitcher& s : final) modes.push_back(&s);
    const std::string split = data.test.empty() ? "train" : "test";
    const std::vector<stitch::Evaluation> measured = stitch::evaluate(model, data, split, modes);

    SeamReportInputs inputs;
    inputs.title = "the demo's 28 pose-only patch decoders on its " + std::to_string(data.rows()) + " shirts, " + split +
                   " split (pca:K chosen on the regularisation split: " + chosen + ")";
    inputs.garment = shirt;
    inputs.evaluations = measured;
    const int row = data.split(split).front();
    body::Body posed = body;
    posed.mesh.V = body.posedVertices(body::Pose::fromLeading(data.inputs.row(row).head(data.poseSize).transpose()));
    for (size_t m : {size_t{0}, size_t{2}, size_t{3}}) {
      const stitch::RowPredictions predicted = stitch::predictRows(model, data, {row}, &final[m]);
      inputs.examples.push_back({"sample " + std::to_string(data.info.settings.first() + row) + ", " +
                                     final[m].mode().name().substr(0, final[m].mode().kind == stitch::StitchKind::Gan ? 3 : std::string::npos),
                                 predicted.positions.front(), data.truth[row].cast<double>(), posed});
    }
    writeSeamReport(report.folder() / "seams", inputs);
    json["chosen"] = chosen;
    json["split"] = split;
    json["modes"] = nlohmann::json::array();
    for (const stitch::Evaluation& e : measured) {
      nlohmann::json m = e.metrics;
      m.erase("patches");
      m["seams"].erase("curves");
      json["modes"].push_back(m);
    }
  });
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
       << " s. The full tables, the sweep of k and a table per cage curve are in seams/report.md. Pictures: the sweep "
          "of k; the first test sample as the mean, the PCA filter and the GAN stitch it, coloured by error, the three "
          "curves of largest normal jump marked; error maps.";
  report.section("Seams", text.str(), {"seams/pca_sweep.png", "seams/worst_seams.png", "seams/error_maps_by_mode.png"});
}

}  // namespace pixelcloth::viz
