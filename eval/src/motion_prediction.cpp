#include "pixelcloth/eval/motion_prediction.h"

#include <chrono>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/motion/glb.h"
#include "pixelcloth/stitch/evaluate.h"

namespace pixelcloth::eval {

namespace fs = std::filesystem;

MotionPrediction predictMotion(const learn::PredictionInputs& inputs, const stitch::Stitcher& stitcher,
                               const motion::Motion& clip, const fs::path& out, const nlohmann::json& info) {
  PIXELCLOTH_CHECK(inputs.data.rows() == clip.frames(),
                   "predict --motion: " << inputs.data.rows() << " rows for " << clip.frames() << " frames");
  PIXELCLOTH_CHECK(!inputs.model->residual(), "predict --motion: the model in "
                                                  << inputs.model->folder().string()
                                                  << " is a residual model, which needs the garment's markers in "
                                                     "every frame: use reconstruct --markers-sequence");
  MotionPrediction result;
  result.frames = clip.frames();
  result.fps = clip.fps;
  std::vector<int> rows(clip.frames());
  for (int f = 0; f < clip.frames(); ++f) rows[f] = f;
  const auto start = std::chrono::steady_clock::now();
  stitch::RowPredictions predicted = stitch::predictRows(*inputs.model, inputs.data, rows, &stitcher);
  result.predictSeconds = core::secondsSince(start);
  result.garment = std::move(predicted.positions);

  // The body of every frame, posed as the model sees it (its pose size), and both moved as the clip's root moves.
  const body::Body body = data::loadDatasetBody(data::DatasetFolder{inputs.data.folder});
  std::vector<body::Pose> poses;
  for (int f = 0; f < clip.frames(); ++f) {
    poses.push_back(body::Pose::fromLeading(inputs.data.inputs.row(f).transpose()));
    result.body.push_back(body.posedVertices(poses.back()));
  }
  result.metrics = motion::temporalMetrics(result.garment, result.body, body.mesh.F, clip.fps);
  const Eigen::Vector3d root = body.skeleton.positions.row(body.skeleton.index("root")).transpose();
  const std::vector<Eigen::MatrixX3d> garmentWorld = motion::withRootMotion(result.garment, clip, root);
  const std::vector<Eigen::MatrixX3d> bodyWorld = motion::withRootMotion(result.body, clip, root);

  core::ensureOutputFolder(out);
  const core::Mesh& garment = inputs.data.garment.mesh;
  motion::AnimatedScene scene{&body,        poses,   clip.rootRotations, clip.rootTranslations, &garment,
                              garmentWorld, clip.fps};
  motion::writeAnimatedGlb(out / "animation.glb", scene);
  motion::writeObjSequence(out / "frames", "garment", garment, garmentWorld);
  core::Mesh garmentBase = garment, bodyBase = body.mesh;
  garmentBase.V = garmentWorld.front();
  bodyBase.V = bodyWorld.front();
  core::writeMesh(out / "garment.obj", garmentBase);
  core::writeMesh(out / "body.obj", bodyBase);
  motion::writePc2(out / "garment.pc2", garmentWorld);
  motion::writePc2(out / "body.pc2", bodyWorld);
  nlohmann::json json = result.metrics.toJson();
  json.update(info);
  json["prediction_ms_per_frame"] = 1000 * result.predictSeconds / clip.frames();
  core::writeJson(out / "metrics.json", json);
  result.files = {"animation.glb", "frames/garment_NNNN.obj", "garment.obj", "body.obj", "garment.pc2", "body.pc2",
                  "metrics.json"};
  return result;
}

}  // namespace pixelcloth::eval
