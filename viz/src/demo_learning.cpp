// The demo's learned models: a whole-garment decoder, the 28 patch decoders and the residual patch decoders trained on
// the demo's simulated shirts, evaluated on its test split beside the marker reconstruction alone.
#include <algorithm>
#include <iomanip>
#include <sstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/learn/training_data.h"
#include "pixelcloth/recon/base.h"
#include "pixelcloth/stitch/evaluate.h"
#include "pixelcloth/viz/demo.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"

namespace pixelcloth::viz {

namespace fs = std::filesystem;

namespace {

struct DemoModel {
  std::string name, folder, label;
  learn::Architecture architecture;
  double width;
  bool residual;
};

/// The demo's three models; epochs and widths sized for about a minute each on two cores.
const std::vector<DemoModel>& demoModels() {
  static const std::vector<DemoModel> models = {
      {"whole", "model_whole", "whole garment, pose in", learn::Architecture::Whole, 0.125, false},
      {"patch", "model_patch", "28 patches, pose in", learn::Architecture::Patch, 0.125, false},
      {"residual_patch", "model_residual_patch", "28 patches, residual on the markers' garment",
       learn::Architecture::Patch, 0.125, true}};
  return models;
}

}  // namespace

void demoLearning(Report& report, const body::Body& body, const DemoOptions& demo) {
  const fs::path datasetFolder = report.folder() / "dataset_tshirt", baseFolder = report.folder() / "bases_tshirt";
  report.step("learning: the marker reconstruction of every T-shirt sample, as the residual models' base", [&] {
    recon::BaseSetOptions options;
    const recon::BaseSetReport bases = recon::writeDatasetBases(datasetFolder, baseFolder, options);
    report.json()["bases_tshirt"] = {{"samples", bases.samples}, {"markers", bases.markers},
                                     {"garment_error_cm", bases.meanErrorCm}, {"seconds", bases.seconds}};
  });
  nlohmann::json& table = report.json()["learning"];
  table = nlohmann::json::object();
  for (const DemoModel& m : demoModels()) {
    report.step("learning: training the " + m.label + " decoder(s)", [&] {
      learn::TrainOptions options;
      options.model.architecture = m.architecture;
      options.model.width = m.width;
      options.epochs = demo.learningEpochs;
      options.batch = 4;
      options.learningRate = 2e-3;
      if (m.residual) {
        options.residual = baseFolder;
        options.model.inputSize = body::kPoseSize + 3 * report.json()["bases_tshirt"]["markers"].get<int>();
      }
      const learn::TrainReport trained = learn::train(datasetFolder, report.freshFolder(m.folder), options);
      const learn::NetworkReport& first = trained.networks.front();
      writePng(report.folder() / m.folder / "training.png",
               renderTrainingCurves(first, m.name + (first.patch >= 0 ? " (patch " + std::to_string(first.patch) + ")"
                                                                       : std::string())));
      table[m.name] = {{"label", m.label},
                       {"width", m.width},
                       {"networks", trained.networks.size()},
                       {"parameters_per_network", learn::summarize(options.model).parameters},
                       {"epochs", options.epochs},
                       {"seconds", trained.seconds}};
    });
  }
  report.step("learning: the models on the test split, beside ground truth", [&] {
    const data::DatasetInfo info = data::readDatasetInfo(datasetFolder);
    const garment::Garment shirt = data::datasetGarment(info);
    std::vector<core::RgbImage> maps;
    std::vector<std::vector<core::RgbImage>> rows;  // per shown sample: ground truth, then each model
    std::vector<int> shown;
    auto posedBody = [&](const learn::TrainingData& data, int row) {
      body::Body posed = body;
      posed.mesh = body.posedMesh(body::Pose::fromLeading(data.inputs.row(row).head(data.poseSize).transpose()));
      return posed;
    };
    for (const DemoModel& m : demoModels()) {
      const learn::TrainedModel model(report.folder() / m.folder, shirt);
      const learn::TrainingData data =
          learn::loadTrainingData(datasetFolder, model.space(), m.residual ? baseFolder : fs::path());
      const data::Split split = data.test.empty() ? data::Split::Train : data::Split::Test;
      const stitch::Evaluation evaluation = stitch::evaluate(model, data, split).front();
      table[m.name]["split"] = data::splitName(split);
      table[m.name]["samples"] = evaluation.metrics["samples"];
      table[m.name]["dataset_samples"] = data.rows();
      table[m.name]["vertex_error_cm"] = evaluation.metrics["vertex_error_cm"];
      table[m.name]["normal_cosine"] = evaluation.metrics["normal_cosine"];
      if (m.residual)
        table["markers_alone"] = {{"split", data::splitName(split)},
                                  {"vertex_error_cm", evaluation.metrics["base_vertex_error_cm"]}};
      // Each map on its own scale, 0 to its 95th percentile: the pose-only models are off by centimetres, the residual
      // one by millimetres.
      const double high = std::max(1e-3, evaluation.vertexErrorQuantileCm(0.95));
      std::ostringstream title;
      title << std::fixed << std::setprecision(2) << m.name << ": " << data::splitName(split) << " error "
            << evaluation.metrics["vertex_error_cm"].get<double>() << " cm, scale 0 to " << high << " cm";
      maps.push_back(renderPatternValues(shirt, evaluation.vertexErrorCm, high, title.str(), 256));
      if (shown.empty()) {  // the split's first two samples, ground truth first
        const std::vector<int>& rowsOfSplit = data.split(split);
        shown.assign(rowsOfSplit.begin(), rowsOfSplit.begin() + std::min<size_t>(2, rowsOfSplit.size()));
        for (int r : shown) {
          garment::Garment truth = shirt;
          truth.mesh.V = data.truth[r].cast<double>();
          const body::Body posed = posedBody(data, r);
          core::RgbImage picture = renderGarmentOnBody(truth, &posed, 220);
          drawText(picture, {8, 8}, "ground truth", {0, 0, 0}, 2);
          rows.push_back({picture});
        }
      }
      const stitch::RowPredictions predicted = stitch::predictRows(model, data, shown);
      for (size_t k = 0; k < shown.size(); ++k) {
        garment::Garment g = shirt;
        g.mesh.V = predicted.positions[k];
        const body::Body posed = posedBody(data, shown[k]);
        core::RgbImage picture = renderGarmentOnBody(g, &posed, 220);
        std::ostringstream label;
        label << std::fixed << std::setprecision(2) << m.name << " "
              << core::meanVertexErrorCm(predicted.positions[k], data.truth[shown[k]]) << " cm";
        drawText(picture, {8, 8}, label.str(), {0, 0, 0}, 2);
        rows[k].push_back(picture);
      }
    }
    std::vector<core::RgbImage> sheets;
    for (const std::vector<core::RgbImage>& row : rows) sheets.push_back(contactSheet(row, static_cast<int>(row.size())));
    core::ensureOutputFolder(report.folder() / "learning");
    writePng(report.folder() / "learning" / "predictions.png", contactSheet(sheets, 1));
    writePng(report.folder() / "learning" / "error_maps.png", contactSheet(maps, 1));
  });
  std::ostringstream text;
  text << std::fixed << std::setprecision(2);
  const std::string split = table["whole"].value("split", "test");
  text << "pixelcloth train and evaluate on the demo's " << table["whole"].value("dataset_samples", 0)
       << " simulated shirts (masked L1 plus the normal loss, Adam; the best epoch chosen on the regularisation "
          "split), mean per-vertex error on the "
       << table["whole"].value("samples", 0) << " samples of the " << split << " split: ";
  for (const DemoModel& m : demoModels()) {
    const nlohmann::json& row = table[m.name];
    text << m.label << " (" << row["networks"].get<int>() << " x " << row["parameters_per_network"].get<long>()
         << " parameters, width " << std::defaultfloat << m.width << std::fixed << ", " << row["epochs"].get<int>()
         << " epochs, " << row["seconds"].get<double>() << " s): " << row["vertex_error_cm"].get<double>() << " cm; ";
  }
  text << "the marker reconstruction alone (the residual models' base): "
       << table["markers_alone"]["vertex_error_cm"].get<double>()
       << " cm. A few minutes of training on a few dozen samples: the models are far from converged, and the full "
          "comparison on 480 samples is in README. Rows: test samples; columns: ground truth, then each model with "
          "its error. Below: mean per-vertex error in pattern space per model, each on its own scale (0 to its 95th "
          "percentile).";
  report.section("Learned models", text.str(), {"learning/predictions.png", "learning/error_maps.png"});
}

}  // namespace pixelcloth::viz
