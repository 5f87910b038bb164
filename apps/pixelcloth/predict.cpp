// pixelcloth predict: garments from a trained model, for a pose (and its markers) or for dataset samples.
#include "pixelcloth/learn/predict.h"

#include <cstdio>
#include <iomanip>
#include <iostream>
#include <memory>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/eval/motion_prediction.h"
#include "pixelcloth/learn/training_data.h"
#include "pixelcloth/motion/motion.h"
#include "pixelcloth/patches/cloth_image.h"
#include "pixelcloth/stitch/evaluate.h"
#include "pixelcloth/viz/motion_pictures.h"
#include "pixelcloth/viz/pictures.h"
#include "prediction_inputs.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
namespace fs = std::filesystem;

struct PredictArgs {
  std::string model, pose, motion, markers, dataset, base, out, engine = "onednn";
  std::vector<int> samples;
  StitchArgs stitch;
};

/// <name>.obj (the garment), <name>.exr (its cloth image of local offsets) and <name>.png (a preview).
void writeGarment(const fs::path& out, const std::string& name, const garment::Garment& garment,
                  const patches::ClothImager& imager, const Eigen::MatrixX3d& positions,
                  const garment::EmbeddedFrames& frames) {
  core::Mesh mesh = garment.mesh;
  mesh.V = positions;
  core::writeMesh(out / (name + ".obj"), mesh);
  patches::ClothImage image = imager.rasterize(garment::offsetsFromPositions(frames, positions).cast<float>());
  patches::writeClothImage(out / (name + ".exr"), image);
  core::writePng(out / (name + ".png"), viz::renderClothImage(image));
}

/// The motion form: every frame of a motion folder predicted, as OBJ frames, PC2 caches of garment and body, the
/// temporal measures and pictures.
void runPredictMotion(const PredictArgs& args) {
  PIXELCLOTH_CHECK(args.pose.empty() && args.samples.empty() && args.markers.empty() && args.base.empty(),
                   "predict --motion: not with --pose, --samples, --markers or --base");
  PIXELCLOTH_CHECK(args.stitch.modes.find(',') == std::string::npos,
                   "predict --stitch " << args.stitch.modes << ": one mode (evaluate compares several)");
  core::checkOutputFolder(args.out);
  core::checkRunFolder(args.out, {"metrics.json", {}, "a predicted motion"});
  const motion::Motion clip = motion::readMotion(args.motion, poseLimits());
  const learn::Engine engine = learn::engineFromName(args.engine, "--engine");
  const learn::PredictionInputs inputs =
      learn::posesPredictionInputs(args.model, clip.poses, args.motion, datasetFolder(args.dataset), engine);
  PIXELCLOTH_CHECK(!inputs.model->residual(), "predict --motion: the model in "
                                                  << args.model
                                                  << " is a residual model, which needs the garment's markers in "
                                                     "every frame: use reconstruct --markers-sequence");
  const std::vector<stitch::Stitcher> stitchers = makeStitchers(args.stitch, inputs);
  const eval::MotionPrediction result =
      eval::predictMotion(inputs, stitchers.front(), clip, args.out,
                          {{"model", args.model},
                           {"motion", args.motion},
                           {"stitch", args.stitch.modes},
                           {"engine", args.engine},
                           {"dataset", fs::absolute(inputs.data.folder).lexically_normal().string()}});
  viz::writeSequencePictures(args.out, data::loadDatasetBody(inputs.data.folder).mesh.F, inputs.data.garment.mesh,
                             result);
  std::cout << "predict: " << sequenceSummary(result, args.out) << "\n";
}

void runPredict(const PredictArgs& args) {
  if (!args.motion.empty()) return runPredictMotion(args);
  PIXELCLOTH_CHECK(args.pose.empty() != args.samples.empty(),
                   "predict: give --pose P.json, or --dataset D with --samples i,j (not both)");
  PIXELCLOTH_CHECK(args.samples.empty() || !args.dataset.empty(), "predict: --samples needs --dataset");
  PIXELCLOTH_CHECK(args.markers.empty() || !args.pose.empty(),
                   "predict: --markers goes with --pose (dataset samples take their markers from the base folder)");
  core::checkOutputFolder(args.out);
  core::checkRunFolder(args.out, {"prediction.json", {}, "a prediction"});
  const learn::Engine engine = learn::engineFromName(args.engine, "--engine");
  const learn::PredictionInputs inputs =
      args.pose.empty()
          ? learn::datasetPredictionInputs(args.model, datasetFolder(args.dataset), args.base, engine)
          : posePredictionInputs(args.model, args.pose, args.markers, datasetFolder(args.dataset), engine);
  std::vector<int> rows;
  for (int sample : args.samples) {
    const int row = inputs.data.info.rowOfSample(sample, "predict --samples");
    rows.push_back(row);
  }
  if (rows.empty()) rows.push_back(0);  // the pose form: one row
  PIXELCLOTH_CHECK(args.stitch.modes.find(',') == std::string::npos,
                   "predict --stitch " << args.stitch.modes << ": one mode (evaluate compares several)");
  const std::vector<stitch::Stitcher> stitchers = makeStitchers(args.stitch, inputs);
  const stitch::RowPredictions predicted = stitch::predictRows(*inputs.model, inputs.data, rows, &stitchers.front());
  core::ensureOutputFolder(args.out);
  const patches::ClothImager imager(inputs.data.garment);
  std::cout << std::fixed << std::setprecision(3);
  // Each garment's posed body beside it, and prediction.json listing both, for pixelcloth view.
  const body::Body body = data::loadDatasetBody(inputs.data.info.where());
  nlohmann::json description = {{"format", "pixelcloth.prediction"},
                                {"model", args.model},
                                {"dataset", fs::absolute(inputs.data.folder).lexically_normal().string()},
                                {"garments", nlohmann::json::array()}};
  for (size_t k = 0; k < rows.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof(name), "sample_%06d", args.samples.empty() ? 0 : args.samples[k]);
    const std::string stem = args.pose.empty() ? name : "garment";
    writeGarment(args.out, stem, inputs.data.garment, imager, predicted.positions[k], inputs.data.frames[rows[k]]);
    core::Mesh posed = body.mesh;
    posed.V = body.posedVertices(
        body::Pose::fromLeading(inputs.data.inputs.row(rows[k]).head(inputs.data.poseSize).transpose()));
    const std::string bodyName = args.pose.empty() ? std::string(name) + "_body.obj" : "body.obj";
    core::writeMesh(fs::path(args.out) / bodyName, posed);
    nlohmann::json entry = {{"file", stem + ".obj"}, {"body", bodyName}};
    if (args.pose.empty()) entry["sample"] = args.samples[k];
    if (!args.markers.empty()) {
      core::writeTextAtomically(fs::path(args.out) / "markers.json", core::readTextFile(args.markers));
      entry["markers"] = "markers.json";
    }
    description["garments"].push_back(entry);
    std::cout << (fs::path(args.out) / (stem + ".obj")).string();
    if (args.pose.empty())
      std::cout << ": " << core::meanVertexErrorCm(predicted.positions[k], inputs.data.truth[rows[k]])
                << " cm mean vertex error";
    std::cout << "\n";
  }
  core::writeJson(fs::path(args.out) / "prediction.json", description);
}
}  // namespace

void registerPredict(CLI::App& app) {
  auto args = std::make_shared<PredictArgs>();
  CLI::App* verb = app.add_subcommand(
      "predict", "Garments from a trained model (pixelcloth train), for a pose or for dataset samples: OBJ, EXR, PNG");
  verb->add_option("--model", args->model, "Model folder (one network, or patch_NN/ folders)")->required();
  verb->add_option("--pose", args->pose, "Pose file (pixelcloth pose); the body and garment are the model's dataset's");
  verb->add_option("--motion", args->motion,
                   "Motion folder (pixelcloth motion import): every frame, as animation.glb (skinned body, garment "
                   "morph targets), an OBJ sequence, PC2 caches of garment and body, strip.png, temporal.png and "
                   "metrics.json (jitter, garment inside the body)");
  verb->add_option("--markers", args->markers, "With --pose, for a residual model: the garment's markers (M.json)");
  verb->add_option("--dataset", args->dataset,
                   "Dataset folder: with --samples, the samples to predict; with --pose, the body and garment "
                   "(default: the model's training dataset)");
  verb->add_option("--samples", args->samples, "With --dataset: sample indices, e.g. 0,5,17")->delimiter(',');
  verb->add_option("--base", args->base,
                   "Residual models: the dataset's base folder (default: the one the model was trained with)");
  verb->add_option("--out", args->out,
                   "Output folder: garment.obj/.exr/.png and body.obj (the posed body), or sample_NNNNNN.* and "
                   "sample_NNNNNN_body.obj per sample; prediction.json lists them (pixelcloth view reads it)")
      ->required();
  addEngineOption(*verb, args->engine);
  addStitchOptions(*verb, args->stitch, false);
  verb->callback([args] { runPredict(*args); });
}

}  // namespace pixelcloth::apps
