#include "pixelcloth/eval/motion_prediction.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <unordered_map>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/parallel.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/motion/glb.h"
#include "pixelcloth/recon/capture_base.h"
#include "pixelcloth/stitch/evaluate.h"

namespace pixelcloth::eval {

namespace fs = std::filesystem;

MotionPrediction writeGarmentSequence(const body::Body& body, const std::vector<body::Pose>& poses,
                                      const core::Mesh& garmentMesh, std::vector<Eigen::MatrixX3d> garment,
                                      std::vector<double> seamGapCm, double predictSeconds, const motion::Motion& clip,
                                      const fs::path& out, const nlohmann::json& info) {
  const int frames = clip.frames();
  PIXELCLOTH_CHECK(static_cast<int>(garment.size()) == frames && static_cast<int>(poses.size()) == frames &&
                       (seamGapCm.empty() || static_cast<int>(seamGapCm.size()) == frames),
                   "garment sequence: " << garment.size() << " garments and " << poses.size() << " poses for " << frames
                                        << " frames");
  MotionPrediction result;
  result.frames = frames;
  result.fps = clip.fps;
  result.predictSeconds = predictSeconds;
  result.garment = std::move(garment);
  for (const body::Pose& pose : poses) result.body.push_back(body.posedVertices(pose));
  result.metrics = motion::temporalMetrics(result.garment, result.body, body.mesh.F, clip.fps);
  // A whole-garment model has no seams between networks: no gap measured.
  if (std::any_of(seamGapCm.begin(), seamGapCm.end(), [](double gap) { return std::isfinite(gap); }))
    result.metrics.seamGapCm = std::move(seamGapCm);

  // Both moved as the clip's root moves.
  const Eigen::Vector3d root = body.skeleton.positions.row(body.skeleton.index("root")).transpose();
  const std::vector<Eigen::MatrixX3d> garmentWorld = motion::withRootMotion(result.garment, clip, root);
  const std::vector<Eigen::MatrixX3d> bodyWorld = motion::withRootMotion(result.body, clip, root);
  core::ensureOutputFolder(out);
  motion::AnimatedScene scene{&body,        poses,   clip.rootRotations, clip.rootTranslations, &garmentMesh,
                              garmentWorld, clip.fps};
  motion::writeAnimatedGlb(out / "animation.glb", scene);
  motion::writeObjSequence(out / "frames", "garment", garmentMesh, garmentWorld);
  core::Mesh garmentBase = garmentMesh, bodyBase = body.mesh;
  garmentBase.V = garmentWorld.front();
  bodyBase.V = bodyWorld.front();
  core::writeMesh(out / "garment.obj", garmentBase);
  core::writeMesh(out / "body.obj", bodyBase);
  motion::writePc2(out / "garment.pc2", garmentWorld);
  motion::writePc2(out / "body.pc2", bodyWorld);
  nlohmann::json json = result.metrics.toJson();
  json.update(info);
  json["prediction_ms_per_frame"] = 1000 * predictSeconds / frames;
  core::writeJson(out / "metrics.json", json);
  result.files = {"animation.glb", "frames/garment_NNNN.obj", "garment.obj", "body.obj", "garment.pc2", "body.pc2",
                  "metrics.json"};
  return result;
}

MotionPrediction predictMotion(const learn::PredictionInputs& inputs, const stitch::Stitcher& stitcher,
                               const motion::Motion& clip, const fs::path& out, const nlohmann::json& info) {
  PIXELCLOTH_CHECK(inputs.data.rows() == clip.frames(),
                   "predict --motion: " << inputs.data.rows() << " rows for " << clip.frames() << " frames");
  std::vector<int> rows(clip.frames());
  for (int f = 0; f < clip.frames(); ++f) rows[f] = f;
  const auto start = std::chrono::steady_clock::now();
  stitch::RowPredictions predicted = stitch::predictRows(*inputs.model, inputs.data, rows, &stitcher, true);
  const double seconds = core::secondsSince(start);

  // The body of every frame, posed as the model sees it (its pose size).
  const body::Body body = data::loadDatasetBody(data::DatasetFolder{inputs.data.folder});
  std::vector<body::Pose> poses;
  for (int f = 0; f < clip.frames(); ++f)
    poses.push_back(body::Pose::fromLeading(inputs.data.inputs.row(f).head(inputs.data.poseSize).transpose()));
  return writeGarmentSequence(body, poses, inputs.data.garment.mesh, std::move(predicted.positions),
                              std::move(predicted.seamGapCm), seconds, clip, out, info);
}

motion::MarkerTrajectories markerTrajectories(const cage::MarkerSet& definition, const cage::Cage& cage,
                                              const std::vector<Eigen::MatrixX3d>& frames,
                                              const cage::CaptureOptions& capture) {
  const auto M = static_cast<Eigen::Index>(definition.markers.size());
  // The definition's markers on each closed curve, which must keep three.
  std::vector<std::vector<Eigen::Index>> closed;
  for (const cage::CageCurve& curve : cage.curves) {
    if (!curve.closed) continue;
    const std::set<int> on(curve.vertices.begin(), curve.vertices.end());
    closed.emplace_back();
    for (Eigen::Index m = 0; m < M; ++m)
      if (on.count(definition.markers[m].vertex)) closed.back().push_back(m);
  }
  motion::MarkerTrajectories out;
  for (size_t f = 0; f < frames.size(); ++f) {
    cage::CaptureOptions frameCapture = capture;
    frameCapture.seed = capture.seed + f;
    const cage::MarkerSet placed = cage::placeMarkers(definition, frames[f], frameCapture);
    // Every marker as it would be seen: the same draws of noise, none dropped.
    frameCapture.dropout = 0;
    const cage::MarkerSet all = cage::placeMarkers(definition, frames[f], frameCapture);
    Eigen::MatrixX3d positions = Eigen::MatrixX3d::Constant(M, 3, std::numeric_limits<double>::quiet_NaN());
    // placeMarkers keeps the definition's order and leaves the dropped markers out.
    for (Eigen::Index m = 0, k = 0; m < M && k < static_cast<Eigen::Index>(placed.markers.size()); ++m)
      if (placed.markers[k].name == definition.markers[m].name) positions.row(m) = placed.markers[k++].position;
    for (const std::vector<Eigen::Index>& markers : closed) {
      int seen = 0;
      for (Eigen::Index m : markers) seen += positions.row(m).allFinite();
      for (auto m = markers.begin(); seen < 3 && m != markers.end(); ++m)
        if (!positions.row(*m).allFinite()) {
          positions.row(*m) = all.markers[*m].position;
          ++seen;
        }
    }
    out.frames.push_back(std::move(positions));
  }
  return out;
}

std::vector<cage::MarkerSet> capturedFrames(const cage::MarkerSet& definition, const cage::Cage& cage,
                                            const motion::MarkerTrajectories& trajectories, const motion::Motion& clip,
                                            const Eigen::Vector3d& rootPosition) {
  const std::string& file = trajectories.source;
  PIXELCLOTH_CHECK(trajectories.numFrames() == clip.frames(), file << ": " << trajectories.numFrames()
                                                                   << " frames, but the motion has " << clip.frames()
                                                                   << " (one row of markers per frame of the motion)");
  PIXELCLOTH_CHECK(trajectories.markers() == static_cast<int>(definition.markers.size()),
                   file << ": " << trajectories.markers() << " markers, expected " << definition.markers.size());
  const std::vector<Eigen::MatrixX3d> local = motion::withoutRootMotion(trajectories.frames, clip, rootPosition);
  std::unordered_map<int, std::string> markerAt;  // garment vertex -> marker name, for messages
  for (const cage::Marker& m : definition.markers) markerAt[m.vertex] = m.name;
  std::vector<cage::MarkerSet> out;
  for (int f = 0; f < clip.frames(); ++f) {
    cage::MarkerSet frame{definition.garment, {}};
    std::unordered_map<int, bool> seen;
    for (size_t m = 0; m < definition.markers.size(); ++m) {
      const Eigen::Vector3d p = local[f].row(static_cast<Eigen::Index>(m)).transpose();
      if (!p.allFinite()) continue;
      cage::Marker marker = definition.markers[m];
      marker.position = p;
      seen[marker.vertex] = true;
      frame.markers.push_back(std::move(marker));
    }
    const std::string where = file + ": frame " + std::to_string(f + 1);
    for (const cage::CageCurve& curve : cage.curves) {
      if (!curve.closed) {
        for (int end : {curve.vertices.front(), curve.vertices.back()}) {
          const auto named = markerAt.find(end);
          PIXELCLOTH_CHECK(seen.count(end), where << ": curve '" << curve.name << "' has no marker at its end ("
                                                  << (named == markerAt.end() ? "no marker is defined there"
                                                                              : "'" + named->second + "' is not seen")
                                                  << "); markers along a curve may drop out, its ends may not");
        }
      } else {
        int count = 0;
        for (int v : curve.vertices) count += static_cast<int>(seen.count(v));
        PIXELCLOTH_CHECK(count >= 3, where << ": closed curve '" << curve.name << "' has " << count
                                           << " markers seen, at least 3 needed");
      }
    }
    out.push_back(std::move(frame));
  }
  return out;
}

std::vector<Eigen::MatrixX3d> reconstructFrames(const recon::GarmentReconstructor& reconstructor,
                                                const std::vector<cage::MarkerSet>& captured,
                                                const std::vector<body::Pose>& poses,
                                                recon::ReconstructionMethod method, int threads,
                                                const std::string& context) {
  PIXELCLOTH_CHECK(captured.size() == poses.size(),
                   context << ": " << captured.size() << " frames of markers and " << poses.size() << " poses");
  const int frames = static_cast<int>(poses.size());
  std::vector<Eigen::MatrixX3d> out(frames);
  core::Progress progress("reconstruct frames", frames);
  core::parallelFor(frames, threads, [&](int f) {
    out[f] = reconstructor.reconstruct(captured[f], poses[f], method, context + ": frame " + std::to_string(f + 1))
                 .positions;
    progress.advance();
  });
  progress.finish();
  return out;
}

void addCaptureBases(learn::PredictionInputs& inputs, const std::vector<cage::MarkerSet>& captured, int threads,
                     const std::string& context) {
  const int frames = inputs.data.rows();
  PIXELCLOTH_CHECK(static_cast<int>(captured.size()) == frames,
                   context << ": " << captured.size() << " frames of markers for " << frames << " poses");
  PIXELCLOTH_CHECK(inputs.model->residual(), "--model " << inputs.model->folder().string()
                                                        << ": a model that takes the pose alone; a capture is "
                                                           "refined by a residual model (train --residual)");
  const recon::CaptureRebuilder rebuilder(inputs.model->baseFolder(), inputs.data.info.where());
  std::vector<Eigen::MatrixX3d> offsets(frames);
  Eigen::MatrixXd features(frames, 3 * static_cast<Eigen::Index>(rebuilder.definition().markers.size()));
  core::Progress progress("bases of the frames", frames);
  core::parallelFor(frames, threads, [&](int f) {
    const body::Pose pose = body::Pose::fromLeading(inputs.data.inputs.row(f).transpose());
    const recon::CaptureBase base = rebuilder.rebuild(captured[f], pose, context + ": frame " + std::to_string(f + 1));
    offsets[f] = base.offsets;
    features.row(f) = base.features.transpose();
    progress.advance();
  });
  progress.finish();
  learn::addPoseBases(inputs, offsets, features);
}

double addTrajectoryBases(learn::PredictionInputs& inputs, const body::Body& body, const cage::MarkerSet& definition,
                          const std::string& markersName, const motion::MarkerTrajectories& trajectories,
                          const motion::Motion& clip, int threads) {
  const cage::Cage cage = cage::garmentCage(inputs.data.garment);
  definition.validate(inputs.data.garment, cage, markersName, false);
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Vector3d root = body.skeleton.positions.row(body.skeleton.index("root")).transpose();
  addCaptureBases(inputs, capturedFrames(definition, cage, trajectories, clip, root), threads, trajectories.source);
  return core::secondsSince(start);
}

}  // namespace pixelcloth::eval
