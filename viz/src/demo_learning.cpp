// The demo's learned models (eval::runDemoLearning) drawn: predictions beside ground truth, error maps, training
// curves, and their figures beside the marker reconstruction alone.
#include <algorithm>
#include <iomanip>
#include <sstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/learn/model.h"
#include "pixelcloth/viz/demo.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"

namespace pixelcloth::viz {

void demoLearning(Report& report, const body::Body& body, const eval::DemoLearning& learning) {
  nlohmann::json& table = report.json()["learning"];
  table = nlohmann::json::object();
  report.json()["bases_tshirt"] = {{"samples", learning.bases.samples},
                                   {"markers", learning.bases.markers},
                                   {"garment_error_cm", learning.bases.meanErrorCm},
                                   {"seconds", learning.bases.seconds}};
  const learn::TrainingData& data = learning.data;
  const garment::Garment& shirt = data.garment;
  auto posedBody = [&](int row) {
    body::Body posed = body;
    posed.mesh = body.posedMesh(body::Pose::fromLeading(data.inputs.row(row).head(data.poseSize).transpose()));
    return posed;
  };
  std::vector<core::RgbImage> maps;
  std::vector<std::vector<core::RgbImage>> rows;  // per shown sample: ground truth, then each model
  for (int r : learning.shown) {
    garment::Garment truth = shirt;
    truth.mesh.V = data.truth[r].cast<double>();
    const body::Body posed = posedBody(r);
    core::RgbImage picture = renderGarmentOnBody(truth, &posed, 220);
    drawText(picture, {8, 8}, "ground truth", {0, 0, 0}, 2);
    rows.push_back({picture});
  }
  for (const eval::DemoModel& m : learning.models) {
    const learn::NetworkReport& first = m.trained.networks.front();
    writePng(m.folder / "training.png",
             renderTrainingCurves(
                 first, m.name + (first.patch >= 0 ? " (patch " + std::to_string(first.patch) + ")" : std::string())));
    const stitch::Evaluation& evaluation = m.evaluation;
    table[m.name] = {{"label", m.label},
                     {"width", m.options.model.width},
                     {"networks", m.trained.networks.size()},
                     {"parameters_per_network", learn::summarize(m.options.model).parameters},
                     {"epochs", m.options.epochs},
                     {"seconds", m.trained.seconds},
                     {"split", data::splitName(m.split)},
                     {"samples", evaluation.metrics["samples"]},
                     {"dataset_samples", data.rows()},
                     {"vertex_error_cm", evaluation.metrics["vertex_error_cm"]},
                     {"normal_cosine", evaluation.metrics["normal_cosine"]}};
    // Each map on its own scale, 0 to its 95th percentile: the pose-only models are off by centimetres, the residual
    // one by millimetres.
    const double high = std::max(1e-3, evaluation.vertexErrorQuantileCm(0.95));
    std::ostringstream title;
    title << std::fixed << std::setprecision(2) << m.name << ": " << data::splitName(m.split) << " error "
          << evaluation.metrics["vertex_error_cm"].get<double>() << " cm, scale 0 to " << high << " cm";
    maps.push_back(renderPatternValues(shirt, evaluation.vertexErrorCm, high, title.str(), 256));
    for (size_t k = 0; k < learning.shown.size(); ++k) {
      garment::Garment g = shirt;
      g.mesh.V = m.shown.positions[k];
      const body::Body posed = posedBody(learning.shown[k]);
      core::RgbImage picture = renderGarmentOnBody(g, &posed, 220);
      std::ostringstream label;
      label << std::fixed << std::setprecision(2) << m.name << " "
            << core::meanVertexErrorCm(m.shown.positions[k], data.truth[learning.shown[k]]) << " cm";
      drawText(picture, {8, 8}, label.str(), {0, 0, 0}, 2);
      rows[k].push_back(picture);
    }
  }
  table["markers_alone"] = {{"split", data::splitName(learning.models.back().split)},
                            {"vertex_error_cm", learning.markersAloneCm}};
  std::vector<core::RgbImage> sheets;
  for (const std::vector<core::RgbImage>& row : rows) sheets.push_back(contactSheet(row, static_cast<int>(row.size())));
  core::ensureOutputFolder(report.folder() / "learning");
  writePng(report.folder() / "learning" / "predictions.png", contactSheet(sheets, 1));
  writePng(report.folder() / "learning" / "error_maps.png", contactSheet(maps, 1));

  std::ostringstream text;
  text << std::fixed << std::setprecision(2);
  const std::string split = table["whole"].value("split", "test");
  text << "pixelcloth train and evaluate on the demo's " << table["whole"].value("dataset_samples", 0)
       << " simulated shirts (masked L1 plus the normal loss, Adam; the best epoch chosen on the regularisation "
          "split), mean per-vertex error on the "
       << table["whole"].value("samples", 0) << " samples of the " << split << " split: ";
  for (const eval::DemoModel& m : learning.models) {
    const nlohmann::json& row = table[m.name];
    text << m.label << " (" << row["networks"].get<int>() << " x " << row["parameters_per_network"].get<long>()
         << " parameters, width " << std::defaultfloat << m.options.model.width << std::fixed << ", "
         << row["epochs"].get<int>() << " epochs, " << row["seconds"].get<double>()
         << " s): " << row["vertex_error_cm"].get<double>() << " cm; ";
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
