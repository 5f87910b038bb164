// pixelcloth evaluate: a trained model's errors on one split of a dataset, with per-vertex error maps.
#include "pixelcloth/stitch/evaluate.h"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/viz/seam_report.h"
#include "prediction_inputs.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct EvaluateArgs {
  std::string model, dataset, split = "test", base, out, engine = "onednn";
  StitchArgs stitch;
};


/// report.md and its pictures: the examples are the split's first sample as the first mode and the best pca:K mode
/// (or the second mode) stitch it.
void writeReport(const EvaluateArgs& args, const learn::PredictionInputs& inputs,
                 const std::vector<stitch::Stitcher>& stitchers, const std::vector<stitch::Evaluation>& evaluations) {
  const learn::TrainingData& data = inputs.data;
  viz::SeamReportInputs report;
  std::ostringstream title, command;
  title << args.model << " on " << args.dataset << ", " << args.split << " split";
  command << "pixelcloth evaluate --model " << args.model << " --dataset " << args.dataset << " --split " << args.split
          << " --stitch " << args.stitch.modes << " --out " << args.out;
  report.title = title.str();
  report.command = command.str();
  report.garment = data.garment;
  report.evaluations = evaluations;
  const int row = data.split(data::splitFromName(args.split, "evaluate --split")).front();
  const int best = stitch::bestPcaMode(evaluations);
  std::vector<size_t> shown = {0};
  if (best > 0) shown.push_back(static_cast<size_t>(best));
  else if (stitchers.size() > 1) shown.push_back(1);
  const body::Body body = data::loadDatasetBody(data.info.where());
  body::Body posed = body;
  posed.mesh.V = body.posedVertices(body::Pose::fromLeading(data.inputs.row(row).head(data.poseSize).transpose()));
  for (size_t m : shown) {
    const stitch::RowPredictions predicted = stitch::predictRows(*inputs.model, data, {row}, &stitchers[m]);
    report.examples.push_back({"sample " + std::to_string(data.info.settings.first() + row) + ", " +
                                   stitchers[m].mode().name(),
                               predicted.positions.front(), data.truth[row].cast<double>(), posed});
  }
  viz::writeSeamReport(args.out, report);
}

void runEvaluate(const EvaluateArgs& args) {
  core::checkOutputFolder(args.out);
  core::checkRunFolder(args.out, {"metrics.json", {}, "an evaluation"});
  const learn::PredictionInputs inputs = learn::datasetPredictionInputs(
      args.model, datasetFolder(args.dataset), args.base, learn::engineFromName(args.engine, "--engine"));
  const std::vector<stitch::Stitcher> stitchers = makeStitchers(args.stitch, inputs);
  std::vector<const stitch::Stitcher*> modes;
  for (const stitch::Stitcher& s : stitchers) modes.push_back(&s);
  const std::vector<stitch::Evaluation> evaluations =
      stitch::evaluate(*inputs.model, inputs.data, data::splitFromName(args.split, "evaluate --split"), modes);
  const stitch::Evaluation& evaluation = evaluations.front();
  nlohmann::json metrics = evaluation.metrics;
  if (evaluations.size() > 1) {
    metrics["stitch_modes"] = nlohmann::json::array();
    for (const stitch::Evaluation& e : evaluations) {
      nlohmann::json m = e.metrics;
      m.erase("patches");
      metrics["stitch_modes"].push_back(m);
    }
  }
  metrics["model"] = args.model;
  metrics["architecture"] = learn::architectureName(inputs.model->architecture());
  metrics["residual"] = inputs.model->residual();
  metrics["dataset"] = args.dataset;
  core::ensureOutputFolder(args.out);
  stitch::writePredictions(args.out, evaluation, inputs.data, metrics);  // the first mode's garments
  core::writeJson(std::filesystem::path(args.out) / "metrics.json", metrics);
  // Blue 0, white 0.5, red 1 cm and more; below, the same stretched to the 95th percentile for models worse than that.
  std::ostringstream title, stretched;
  title << std::fixed << std::setprecision(3) << args.split << " split, " << metrics["samples"].get<int>()
        << " samples: mean vertex error " << metrics["vertex_error_cm"].get<double>() << " cm (scale 0 to 1 cm)";
  const double high = std::max(1e-3, evaluation.vertexErrorQuantileCm(0.95));
  stretched << std::fixed << std::setprecision(2) << "the same, scale 0 to " << high << " cm (95th percentile)";
  core::writePng(std::filesystem::path(args.out) / "error_maps.png",
                 viz::contactSheet({viz::renderPatternValues(inputs.data.garment, evaluation.vertexErrorCm, 1.0,
                                                             title.str(), 384, true),
                                    viz::renderPatternValues(inputs.data.garment, evaluation.vertexErrorCm, high,
                                                             stretched.str(), 384, true)},
                                   1));
  writeReport(args, inputs, stitchers, evaluations);
  for (const stitch::Evaluation& e : evaluations) {
    const nlohmann::json& m = e.metrics;
    std::cout << std::fixed << std::setprecision(3) << args.split << ", " << m["stitch"].get<std::string>() << ": "
              << m["samples"].get<int>() << " samples, vertex error " << m["vertex_error_cm"].get<double>()
              << " cm, normal cosine " << m["normal_cosine"].get<double>() << "; seams: gap "
              << viz::figureText(m["seams"]["gap_cm"]["mean"]) << " cm (max " << viz::figureText(m["seams"]["gap_cm"]["max"])
              << "), normal jump " << viz::figureText(m["seams"]["normal_jump_deg"], 2) << " deg, error near seams "
              << viz::figureText(m["seams"]["near_seam_error_cm"]) << " cm, interior "
              << viz::figureText(m["seams"]["interior_error_cm"]) << " cm";
    if (inputs.model->residual())
      std::cout << " (marker reconstruction alone: " << m["base_vertex_error_cm"].get<double>() << " cm)";
    std::cout << "\n";
  }
  std::cout << "-> " << args.out << "/{metrics.json, predictions.npy, error_maps.png, report.md}\n";
}
}  // namespace

void registerEvaluate(CLI::App& app) {
  auto args = std::make_shared<EvaluateArgs>();
  CLI::App* verb = app.add_subcommand(
      "evaluate", "A trained model's errors on a dataset split: metrics.json and per-vertex error maps");
  verb->add_option("--model", args->model, "Model folder (pixelcloth train)")->required();
  verb->add_option("--dataset", args->dataset, "Dataset folder")->required();
  verb->add_option("--split", args->split, "train, regularisation or test")
      ->check(CLI::IsMember({"train", "regularisation", "test"}))
      ->capture_default_str();
  verb->add_option("--base", args->base,
                   "Residual models: the dataset's base folder (default: the one the model was trained with)");
  verb->add_option("--out", args->out,
                   "Output folder: metrics.json, predictions.npy (the first mode's garments, for pixelcloth view), "
                   "error_maps.png, report.md (stitch modes, seams per curve, the PCA "
                   "sweep, error maps, the worst seams) and its pictures")
      ->required();
  addEngineOption(*verb, args->engine);
  addStitchOptions(*verb, args->stitch, true);
  verb->callback([args] { runEvaluate(*args); });
}

}  // namespace pixelcloth::apps
