#include "prediction_inputs.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/recon/capture_base.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace fs = std::filesystem;

void addEngineOption(CLI::App& verb, std::string& engine) {
  verb.add_option("--engine", engine,
                  "What runs the networks: onednn (compiled once, fast) or libtorch (its modules, the reference)")
      ->capture_default_str()
      ->check(CLI::IsMember({"onednn", "libtorch"}));
}

void addStitchOptions(CLI::App& verb, StitchArgs& args, bool several) {
  verb.add_option("--stitch", args.modes,
                  std::string("How the patch networks' predictions become one garment: mean, feather (weights falling "
                              "off outside each patch), pca:K (the mean projected on K principal components of the "
                              "training split) or gan:DIR (a blender from train --model gan)") +
                      (several ? "; several separated by commas, each measured on the same predictions" : ""))
      ->capture_default_str();
  verb.add_option("--pca", args.pca,
                  "PCA filter folder for pca:K (pixelcloth pca); default: the model folder's pca/, fitted on the "
                  "dataset's train split on first use");
  verb.add_option("--pca-rank", args.pcaRank,
                  "Components kept when the filter is fitted here (0: min(2048, train samples, 3 x vertices))")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

std::vector<stitch::Stitcher> makeStitchers(const StitchArgs& args, const learn::PredictionInputs& inputs) {
  const std::vector<stitch::StitchMode> modes = stitch::parseStitchModes(args.modes, "--stitch");
  std::shared_ptr<const stitch::PcaFilter> pca;
  if (std::any_of(modes.begin(), modes.end(),
                  [](const stitch::StitchMode& m) { return m.kind == stitch::StitchKind::Pca; }))
    pca = std::make_shared<const stitch::PcaFilter>(
        stitch::loadOrFitPcaFilter(inputs.data, inputs.model->folder(), args.pca, args.pcaRank));
  std::vector<stitch::Stitcher> stitchers;
  for (const stitch::StitchMode& mode : modes) stitchers.emplace_back(inputs.data.garment, mode, pca);
  return stitchers;
}

learn::PredictionInputs posePredictionInputs(const fs::path& modelFolder, const fs::path& posePath,
                                             const fs::path& markersPath, const data::DatasetFolder& dataset,
                                             learn::Engine engine) {
  const body::Pose pose = body::readPose(posePath, poseLimits());
  learn::PredictionInputs out = learn::posePredictionInputs(modelFolder, pose, posePath.string(), dataset, engine);
  if (out.model->residual()) {
    PIXELCLOTH_CHECK(!markersPath.empty(), "predict: the model in " << modelFolder.string()
                                                                    << " is a residual model: give the garment's "
                                                                       "markers too (--markers M.json)");
    const body::Pose leading = body::Pose::fromLeading(out.data.inputs.row(0).transpose());
    const recon::CaptureBase base = recon::baseOfCapture(out.model->baseFolder(), out.data.info.where(),
                                                         cage::readMarkers(markersPath), leading, markersPath.string());
    learn::addPoseBase(out, base.offsets, base.features);
  } else {
    PIXELCLOTH_CHECK(markersPath.empty(), "--markers " << markersPath.string() << ": the model in "
                                                       << modelFolder.string() << " takes the pose alone");
  }
  return out;
}

std::string sequenceSummary(const eval::MotionPrediction& sequence, const fs::path& out) {
  const motion::TemporalMetrics& m = sequence.metrics;
  std::ostringstream text;
  text << std::fixed << std::setprecision(3) << sequence.frames << " frames at " << sequence.fps << " fps in "
       << sequence.predictSeconds << " s (" << 1000 * sequence.predictSeconds / sequence.frames
       << " ms a frame); garment jitter " << m.meanGarmentJitterCm() << " cm (body " << m.meanBodyJitterCm()
       << " cm); ";
  if (std::isfinite(m.meanSeamGapCm())) text << "seam gap " << m.meanSeamGapCm() << " cm; ";
  text << "garment inside the body in " << m.framesWithInside() << " frames -> " << out.string() << "/{";
  for (const std::string& file : sequence.files) text << file << ", ";
  text << "strip.png, temporal.png}";
  return text.str();
}

}  // namespace pixelcloth::apps
