// The demo's seams: the pose-only patch decoders' predictions stitched by the plain mean, feathered weights, the PCA
// filter at the k chosen on the regularisation split, and a GAN blender trained here; measured on the test split and
// written as a seam report (seams/report.md) with the paper's tables on the demo's shirts.
#include <iomanip>
#include <sstream>
#include <tuple>

#include "pixelcloth/data/dataset.h"
#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/learn/training_data.h"
#include "pixelcloth/stitch/evaluate.h"
#include "pixelcloth/stitch/gan.h"
#include "pixelcloth/stitch/pca_filter.h"
#include "pixelcloth/stitch/stitcher.h"
#include "pixelcloth/viz/demo.h"
#include "pixelcloth/viz/seam_report.h"

namespace pixelcloth::viz {

namespace fs = std::filesystem;

namespace {

/// Train and test error of a model folder: "| name | train cm | test cm | normal cosine distance (test) |".
std::string tableRow(const std::string& name, const fs::path& folder, const fs::path& dataset,
                     const garment::Garment& shirt, nlohmann::json& json) {
  const learn::TrainedModel model(folder, shirt);
  const learn::TrainingData data = learn::loadTrainingData(dataset, model.space(), fs::path());
  const nlohmann::json train = stitch::evaluate(model, data, data::Split::Train).front().metrics;
  const nlohmann::json test =
      stitch::evaluate(model, data, data.test.empty() ? data::Split::Train : data::Split::Test).front().metrics;
  json[name] = {{"train_vertex_error_cm", train["vertex_error_cm"]},
                {"test_vertex_error_cm", test["vertex_error_cm"]},
                {"test_normal_cosine_distance", test["normal_cosine_distance"]}};
  std::ostringstream row;
  row << std::fixed << std::setprecision(3) << "| " << name << " | " << train["vertex_error_cm"].get<double>() << " | "
      << test["vertex_error_cm"].get<double>() << " | " << std::setprecision(4)
      << test["normal_cosine_distance"].get<double>() << " |\n";
  return row.str();
}

/// The paper's Tables 1 and 2 and its whole-against-patches comparison on the demo's shirts: the whole-garment decoder
/// with L1, L2 and L2 plus the normal loss; the fully connected baselines direct and through principal components in
/// the three spaces (these models are trained here, a few seconds each); the whole and patch decoders of
/// demoLearning. Markdown.
std::string paperTables(Report& report, const fs::path& dataset, const garment::Garment& shirt, int epochs) {
  nlohmann::json& json = report.json()["paper_tables"];
  const int trainSamples = static_cast<int>(learn::loadTrainingData(dataset, learn::OffsetSpace::Local, {}).train.size());
  auto train = [&](const std::string& folder, learn::Architecture architecture, learn::ImageLoss loss,
                   double normalWeight, learn::OffsetSpace space) {
    learn::TrainOptions options;
    options.model.architecture = architecture;
    options.model.width = architecture == learn::Architecture::Whole ? 0.125 : 0.25;
    options.model.pcaComponents = std::min(128, trainSamples);
    options.loss = loss;
    options.normalWeight = normalWeight;
    options.space = space;
    options.epochs = epochs;
    options.batch = 4;
    options.learningRate = 2e-3;
    learn::train(dataset, report.freshFolder(fs::path("paper_tables") / folder), options);
    return report.folder() / "paper_tables" / folder;
  };
  std::ostringstream md;
  const std::string header = "| model | train error (cm) | test error (cm) | test normal cosine distance |\n|---|---|---|---|\n";
  md << "## The paper's tables on the demo's shirts\n\n" << trainSamples << " train samples, " << epochs
     << " epochs each; far from the paper's scale, so read the orderings, not the figures.\n\n"
     << "Table 1, the whole-garment decoder (width 0.125) by loss:\n\n" << header;
  for (const auto& [name, loss, weight] :
       {std::tuple<const char*, learn::ImageLoss, double>{"L1", learn::ImageLoss::L1, 0.0},
        {"L2", learn::ImageLoss::L2, 0.0},
        {"L2 + normal", learn::ImageLoss::L2, 0.01}})
    md << tableRow(name, train(std::string("whole_") + name, learn::Architecture::Whole, loss, weight,
                               learn::OffsetSpace::Local),
                   dataset, shirt, json["table1"]);
  md << "\nWhole garment against patches (the decoders of the Learned models section, L1 + normal):\n\n" << header;
  md << tableRow("whole-garment decoder", report.folder() / "model_whole", dataset, shirt, json["whole_vs_patches"]);
  md << tableRow("28 patch decoders", report.folder() / "model_patch", dataset, shirt, json["whole_vs_patches"]);
  md << "\nTable 2, the fully connected baselines (2 x 256 ReLU at width 0.25, L1), direct and through "
     << std::min(128, trainSamples) << " principal components, in the three spaces:\n\n" << header;
  for (const learn::OffsetSpace space :
       {learn::OffsetSpace::Local, learn::OffsetSpace::Root, learn::OffsetSpace::Positions})
    for (const learn::Architecture architecture : {learn::Architecture::FullyConnected, learn::Architecture::FullyConnectedPca}) {
      const std::string name = std::string(learn::architectureName(architecture)) + ", " + learn::offsetSpaceName(space);
      md << tableRow(name,
                     train(std::string(learn::architectureName(architecture)) + "_" + learn::offsetSpaceName(space),
                           architecture, learn::ImageLoss::L1, 0.0, space),
                     dataset, shirt, json["table2"]);
    }
  return md.str();
}

}  // namespace

void demoSeams(Report& report, const body::Body& body, const DemoOptions& demo) {
  const fs::path datasetFolder = report.folder() / "dataset_tshirt", patchFolder = report.folder() / "model_patch",
                 ganFolder = report.folder() / "model_gan";
  const garment::Garment shirt = data::datasetGarment(data::readDatasetInfo(datasetFolder));
  const learn::TrainedModel model(patchFolder, shirt);
  const learn::TrainingData data = learn::loadTrainingData(datasetFolder, model.space(), fs::path());
  nlohmann::json& json = report.json()["seams"];
  std::string tables;
  report.step("seams: the paper's tables (losses, whole against patches, the baselines in three spaces)",
              [&] { tables = paperTables(report, datasetFolder, shirt, demo.learningEpochs); });
  report.step("seams: a GAN blender of the patch decoders' stitched predictions", [&] {
    stitch::GanOptions options;
    options.width = 0.0625;
    options.epochs = 3;
    const stitch::GanReport gan = stitch::trainGan(model, data, options, report.freshFolder(ganFolder.filename()));
    json["gan"] = {{"width", options.width}, {"epochs", options.epochs}, {"best_epoch", gan.bestEpoch},
                   {"seconds", gan.seconds}, {"parameters", stitch::ganSummary(options.width)["generator"]["parameters"]}};
  });
  report.step("seams: every stitch mode, k chosen on the regularisation split, measured on the test split", [&] {
    auto pca = std::make_shared<stitch::PcaFilter>(stitch::PcaFilter::fit(data));
    pca->save(stitch::defaultPcaFolder(patchFolder));
    std::vector<stitch::Stitcher> sweep;
    for (const stitch::StitchMode& mode : stitch::pcaSweepModes(pca->rank())) sweep.emplace_back(shirt, mode, pca);
    std::vector<const stitch::Stitcher*> modes;
    for (const stitch::Stitcher& s : sweep) modes.push_back(&s);
    const std::vector<stitch::Evaluation> chosenOn = stitch::evaluate(model, data, data::Split::Regularisation, modes);
    const int best = stitch::bestPcaMode(chosenOn);
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
    const data::Split split = data.test.empty() ? data::Split::Train : data::Split::Test;
    const std::vector<stitch::Evaluation> measured = stitch::evaluate(model, data, split, modes);

    SeamReportInputs inputs;
    inputs.title = "the demo's 28 pose-only patch decoders on its " + std::to_string(data.rows()) + " shirts, " +
                   data::splitName(split) + " split (pca:K chosen on the regularisation split: " + chosen + ")";
    inputs.garment = shirt;
    inputs.evaluations = measured;
    inputs.extra = tables;
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
    json["split"] = data::splitName(split);
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
       << " s. The full tables, the sweep of k, a table per cage curve, and the paper's Tables 1 and 2 and its "
          "whole-against-patches comparison on these shirts are in seams/report.md. Pictures: the sweep "
          "of k; the first test sample as the mean, the PCA filter and the GAN stitch it, coloured by error, the three "
          "curves of largest normal jump marked; error maps.";
  report.section("Seams", text.str(), {"seams/pca_sweep.png", "seams/worst_seams.png", "seams/error_maps_by_mode.png"});
}

}  // namespace pixelcloth::viz
