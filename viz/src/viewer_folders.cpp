// The viewer's scenes of each kind of output folder.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>

#include "pixelcloth/body/body.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/motion/sequence.h"
#include "pixelcloth/motion/trajectories.h"
#include "pixelcloth/viz/viewer.h"

namespace pixelcloth::viz {

namespace {
namespace fs = std::filesystem;

/// A path that a folder's JSON records as it was given: absolute, else relative to the current folder, else to the
/// recording folder or a folder above it (a report's paths are relative to the report). Throws InputError naming the
/// file and key when none exists.
fs::path recordedPath(const nlohmann::json& json, const std::string& key, const fs::path& file) {
  PIXELCLOTH_CHECK(json.contains(key) && json[key].is_string(),
                   file.string() << ": no \"" << key << "\" (the folder the viewer needs to read)");
  const fs::path given = json[key].get<std::string>();
  if (fs::exists(given)) return given;
  for (fs::path above = fs::absolute(file).lexically_normal().parent_path(); given.is_relative();
       above = above.parent_path()) {
    if (fs::exists(above / given)) return above / given;
    if (above == above.root_path()) break;
  }
  throw core::InputError(file.string() + ": \"" + key + "\" names " + given.string() +
                         ", which is not found (relative to the current folder or " + file.parent_path().string() +
                         ")");
}

/// The folder's own name, also for "dir/" and ".".
std::string folderName(const fs::path& folder) {
  fs::path absolute = fs::absolute(folder).lexically_normal();
  if (absolute.filename().empty()) absolute = absolute.parent_path();
  return absolute.filename().string();
}

bool isFormat(const fs::path& file, const std::string& format) {
  if (!fs::is_regular_file(file)) return false;
  const nlohmann::json json = core::readJson(file);
  return json.is_object() && json.value("format", std::string()) == format;
}

std::vector<int> spreadRows(int rows, int count) {
  std::vector<int> picked;
  const int n = std::min(rows, std::max(1, count));
  for (int k = 0; k < n; ++k) picked.push_back(static_cast<int>(static_cast<long long>(k) * rows / n));
  return picked;
}

Eigen::VectorXd errorsCm(const Eigen::MatrixX3d& shown, const Eigen::MatrixX3d& truth) {
  return 100 * (shown - truth).rowwise().norm();
}

/// The parts every scene of one garment shares.
struct GarmentContext {
  garment::Garment garment;
  Eigen::VectorXi patches;
};

GarmentContext garmentContext(garment::Garment garment) {
  GarmentContext context{std::move(garment), {}};
  context.patches = patchOfVertex(context.garment);
  return context;
}

ViewScene garmentScene(const GarmentContext& context, const std::string& name, const std::string& group) {
  ViewScene scene;
  scene.name = name;
  scene.group = group;
  scene.garmentFaces = context.garment.mesh.F;
  scene.patchOfVertex = context.patches;
  return scene;
}

void addBody(ViewScene& scene, const body::Body& body, const Eigen::VectorXf& pose) {
  scene.bodyFaces = body.mesh.F;
  scene.bodyFrames = {body.posedVertices(body::Pose::fromLeading(pose))};
}

/// A dataset with its body and garment, as the scenes of its samples need them.
struct OpenedDataset {
  data::Dataset dataset;
  body::Body body;
  GarmentContext context;
};

OpenedDataset openWithBody(const fs::path& folder) {
  data::Dataset dataset = data::openDataset(folder);
  body::Body body = data::loadDatasetBody(dataset.info.where());
  GarmentContext context = garmentContext(data::datasetGarment(dataset.info));
  return {std::move(dataset), std::move(body), std::move(context)};
}

/// A dataset (generate, dataset import): its samples on their posed bodies.
std::vector<ViewScene> datasetScenes(const fs::path& folder, const std::string& group, const ViewOptions& options) {
  const auto [dataset, body, context] = openWithBody(folder);
  std::vector<ViewScene> scenes;
  for (int row : spreadRows(dataset.rows(), options.maxScenes)) {
    const int sample = dataset.info.settings.first() + row;
    ViewScene scene = garmentScene(
        context,
        "sample " + std::to_string(sample) + " (" + data::splitName(static_cast<data::Split>(dataset.split[row])) + ")",
        group);
    addBody(scene, body, dataset.pose(row));
    const Eigen::MatrixX3d positions = dataset.positionsOf(row).cast<double>();
    scene.garments.push_back({"simulated", false, {positions}, {}});
    scene.curves = viewCurves(context.garment, positions, nullptr);
    scene.curveMeasure = "fold angle";
    scene.info = {{"dataset", folder.string()}, {"sample", sample}};
    scenes.push_back(std::move(scene));
  }
  return scenes;
}

/// evaluate: the split's predictions (predictions.npy) against the dataset's ground truth.
std::vector<ViewScene> evaluationScenes(const fs::path& folder, const std::string& group, const ViewOptions& options) {
  const fs::path metricsFile = folder / "metrics.json";
  const nlohmann::json metrics = core::readJson(metricsFile);
  const fs::path datasetPath = recordedPath(metrics, "dataset", metricsFile);
  const auto [dataset, body, context] = openWithBody(datasetPath);
  const int V = context.garment.mesh.numVertices();
  PIXELCLOTH_CHECK(metrics.contains("rows") && metrics["rows"].is_array(),
                   metricsFile.string() << ": no \"rows\" (the samples of predictions.npy)");
  const std::vector<int> samples = metrics["rows"].get<std::vector<int>>();
  // Shape and dtype from the header, before the data is read.
  const core::NpyHeader header = core::readNpyHeader(folder / "predictions.npy");
  PIXELCLOTH_CHECK(header.shape == std::vector<std::int64_t>({static_cast<std::int64_t>(samples.size()), V, 3}),
                   (folder / "predictions.npy").string() << ": shape " << header.shapeString() << ", expected ("
                                                         << samples.size() << ", " << V << ", 3)");
  const core::NpyArray predictions = core::readNpy(folder / "predictions.npy");
  const float* values = predictions.data<float>();
  std::vector<ViewScene> scenes;
  for (int k : spreadRows(static_cast<int>(samples.size()), options.maxScenes)) {
    const int row = dataset.info.rowOfSample(samples[k], metricsFile.string() + " rows");
    Eigen::MatrixX3d predicted(V, 3);
    for (int v = 0; v < V; ++v)
      for (int c = 0; c < 3; ++c) predicted(v, c) = values[(static_cast<size_t>(k) * V + v) * 3 + c];
    const Eigen::MatrixX3d truth = dataset.positionsOf(row).cast<double>();
    ViewScene scene = garmentScene(context, "sample " + std::to_string(samples[k]), group);
    addBody(scene, body, dataset.pose(row));
    scene.garments.push_back({"prediction (" + metrics.value("stitch", std::string("mean")) + ")",
                              false,
                              {predicted},
                              errorsCm(predicted, truth)});
    scene.garments.push_back({"ground truth", true, {truth}, {}});
    scene.curves = viewCurves(context.garment, predicted, &truth);
    scene.info = {{"model", metrics.value("model", std::string())},
                  {"split", metrics.value("split", std::string())},
                  {"split_vertex_error_cm", metrics.value("vertex_error_cm", 0.0)},
                  {"sample", samples[k]}};
    scenes.push_back(std::move(scene));
  }
  return scenes;
}

/// predict --pose / --samples: prediction.json lists each garment, its posed body and its sample.
std::vector<ViewScene> predictionScenes(const fs::path& folder, const std::string& group) {
  const fs::path file = folder / "prediction.json";
  const nlohmann::json description = core::readJson(file);
  const fs::path datasetPath = recordedPath(description, "dataset", file);
  const data::DatasetInfo info = data::readDatasetInfo(datasetPath);
  const GarmentContext context = garmentContext(data::datasetGarment(info));
  std::optional<data::Dataset> dataset;
  PIXELCLOTH_CHECK(description.contains("garments") && description["garments"].is_array(),
                   file.string() << ": no \"garments\" list");
  std::vector<ViewScene> scenes;
  for (const nlohmann::json& entry : description["garments"]) {
    const core::Mesh garment = core::readMesh(folder / entry.at("file").get<std::string>());
    const core::Mesh body = core::readMesh(folder / entry.at("body").get<std::string>());
    PIXELCLOTH_CHECK(garment.numVertices() == context.garment.mesh.numVertices(),
                     (folder / entry.at("file").get<std::string>()).string()
                         << ": " << garment.numVertices() << " vertices, expected "
                         << context.garment.mesh.numVertices() << " (the garment of " << datasetPath.string() << ")");
    ViewScene scene = garmentScene(context, entry.at("file").get<std::string>(), group);
    scene.bodyFaces = body.F;
    scene.bodyFrames = {body.V};
    if (entry.contains("sample") && entry["sample"].is_number_integer()) {
      if (!dataset) dataset = data::openDataset(datasetPath);
      const Eigen::MatrixX3d truth =
          dataset->positionsOf(dataset->info.rowOfSample(entry["sample"].get<int>(), file.string())).cast<double>();
      scene.garments.push_back({"prediction", false, {garment.V}, errorsCm(garment.V, truth)});
      scene.garments.push_back({"ground truth", true, {truth}, {}});
      scene.curves = viewCurves(context.garment, garment.V, &truth);
    } else {
      scene.garments.push_back({"prediction", false, {garment.V}, {}});
      scene.curves = viewCurves(context.garment, garment.V, nullptr);
      scene.curveMeasure = "fold angle";
    }
    if (entry.contains("markers") && entry["markers"].is_string()) {
      const cage::MarkerSet markers = cage::readMarkers(folder / entry["markers"].get<std::string>());
      Eigen::MatrixX3d points(markers.markers.size(), 3);
      for (size_t m = 0; m < markers.markers.size(); ++m) points.row(m) = markers.markers[m].position.transpose();
      scene.markers = {points};
    }
    scene.info = {{"model", description.value("model", std::string())}};
    scenes.push_back(std::move(scene));
  }
  return scenes;
}

/// reconstruct --dataset: every method's garment of each sample against ground truth, with the markers.
std::vector<ViewScene> reconstructionScenes(const fs::path& folder, const std::string& group) {
  const fs::path metricsFile = folder / "metrics.json";
  const nlohmann::json metrics = core::readJson(metricsFile);
  const fs::path datasetPath = recordedPath(metrics, "dataset", metricsFile);
  const auto [dataset, body, context] = openWithBody(datasetPath);
  std::optional<cage::MarkerSet> markers;
  if (fs::exists(folder / "markers.json")) markers = cage::readMarkers(folder / "markers.json");
  std::vector<fs::path> samples;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    if (entry.is_directory() && entry.path().filename().string().rfind("sample_", 0) == 0 &&
        fs::exists(entry.path() / "truth.obj"))
      samples.push_back(entry.path());
  std::sort(samples.begin(), samples.end());
  std::vector<ViewScene> scenes;
  for (const fs::path& sampleFolder : samples) {
    const int sample = std::stoi(sampleFolder.filename().string().substr(7));
    const int row = dataset.info.rowOfSample(sample, sampleFolder.string());
    const Eigen::MatrixX3d truth = core::readMesh(sampleFolder / "truth.obj").V;
    ViewScene scene = garmentScene(context, "sample " + std::to_string(sample), group);
    addBody(scene, body, dataset.pose(row));
    std::vector<fs::path> methods;
    for (const fs::directory_entry& entry : fs::directory_iterator(sampleFolder))
      if (entry.path().extension() == ".obj" && entry.path().stem() != "truth") methods.push_back(entry.path());
    // The paper's method first: the anisotropic spline fill, then the others by name.
    std::sort(methods.begin(), methods.end(), [](const fs::path& a, const fs::path& b) {
      const bool aFirst = a.stem() == "spline_anisotropic", bFirst = b.stem() == "spline_anisotropic";
      return aFirst != bFirst ? aFirst : a < b;
    });
    for (const fs::path& method : methods) {
      const Eigen::MatrixX3d positions = core::readMesh(method).V;
      PIXELCLOTH_CHECK(positions.rows() == truth.rows(),
                       method.string() << ": " << positions.rows() << " vertices, expected " << truth.rows());
      scene.garments.push_back({method.stem().string(), false, {positions}, errorsCm(positions, truth)});
    }
    scene.garments.push_back({"ground truth", true, {truth}, {}});
    scene.curves = viewCurves(context.garment, scene.garments.front().frames.front(), &truth);
    if (markers) {
      Eigen::MatrixX3d points(markers->markers.size(), 3);
      for (size_t m = 0; m < markers->markers.size(); ++m) points.row(m) = truth.row(markers->markers[m].vertex);
      scene.markers = {points};
    }
    scene.info = {{"sample", sample}, {"markers", metrics.value("markers", 0)}, {"dataset", datasetPath.string()}};
    scenes.push_back(std::move(scene));
  }
  PIXELCLOTH_CHECK(!scenes.empty(), folder.string() << ": no sample_NNNNNN/truth.obj (reconstruct --dataset writes "
                                                       "them)");
  return scenes;
}

/// predict --motion, reconstruct --markers-sequence: the garment and body caches, markers when captured.
std::vector<ViewScene> sequenceScenes(const fs::path& folder, const std::string& group) {
  const fs::path metricsFile = folder / "metrics.json";
  const nlohmann::json metrics = core::readJson(metricsFile);
  const core::Mesh garmentMesh = core::readMesh(folder / "garment.obj");
  const core::Mesh bodyMesh = core::readMesh(folder / "body.obj");
  const std::vector<Eigen::MatrixX3f> garmentFrames = motion::readPc2(folder / "garment.pc2");
  const std::vector<Eigen::MatrixX3f> bodyFrames = motion::readPc2(folder / "body.pc2");
  PIXELCLOTH_CHECK(!garmentFrames.empty() && garmentFrames.size() == bodyFrames.size() &&
                       garmentFrames.front().rows() == garmentMesh.numVertices() &&
                       bodyFrames.front().rows() == bodyMesh.numVertices(),
                   folder.string() << ": garment.pc2 holds " << garmentFrames.size() << " frames of "
                                   << (garmentFrames.empty() ? 0 : garmentFrames.front().rows())
                                   << " vertices and body.pc2 " << bodyFrames.size()
                                   << " frames; expected as many frames of garment.obj's " << garmentMesh.numVertices()
                                   << " and body.obj's " << bodyMesh.numVertices() << " vertices");
  ViewScene scene;
  scene.name = folderName(folder);
  scene.group = group;
  scene.fps = metrics.value("fps", 30.0);
  scene.garmentFaces = garmentMesh.F;
  scene.bodyFaces = bodyMesh.F;
  ViewGarment garment{metrics.contains("markers_sequence") ? "reconstruction" : "prediction", false, {}, {}};
  for (const Eigen::MatrixX3f& f : garmentFrames) garment.frames.push_back(f.cast<double>());
  for (const Eigen::MatrixX3f& f : bodyFrames) scene.bodyFrames.push_back(f.cast<double>());
  // The garment's patches and cage: from the dataset the model was trained on, else the marker file's garment.
  std::optional<garment::Garment> pattern;
  if (metrics.contains("dataset") && metrics["dataset"].is_string())
    pattern = data::datasetGarment(data::readDatasetInfo(recordedPath(metrics, "dataset", metricsFile)));
  std::optional<cage::MarkerSet> markers;
  if (metrics.contains("markers") && metrics["markers"].is_string())
    markers = cage::readMarkers(recordedPath(metrics, "markers", metricsFile));
  if (!pattern && markers) pattern = garment::resolveGarment(markers->garment, metricsFile.string() + " markers");
  if (pattern && pattern->mesh.numVertices() == garmentMesh.numVertices()) {
    scene.patchOfVertex = patchOfVertex(*pattern);
    scene.curves = viewCurves(*pattern, garment.frames.front(), nullptr);
    scene.curveMeasure = "fold angle (first frame)";
  }
  if (markers && metrics.contains("markers_sequence")) {
    const motion::MarkerTrajectories trajectories = motion::readMarkerTrajectories(
        recordedPath(metrics, "markers_sequence", metricsFile), static_cast<int>(markers->markers.size()),
        metrics["markers"].get<std::string>());
    PIXELCLOTH_CHECK(trajectories.numFrames() == static_cast<int>(garment.frames.size()),
                     trajectories.source << ": " << trajectories.numFrames() << " frames, expected "
                                         << garment.frames.size() << " (" << folder.string() << ")");
    scene.markers = trajectories.frames;
  }
  scene.garments.push_back(std::move(garment));
  for (const char* key : {"model", "motion", "stitch"})
    if (metrics.contains(key)) scene.info[key] = metrics[key];
  for (const char* key : {"garment_jitter_cm", "body_jitter_cm", "seam_gap_cm"})
    if (metrics.contains(key) && metrics[key].is_object() && metrics[key].contains("mean"))
      scene.info[std::string(key) + " (mean)"] = metrics[key]["mean"];
  return {scene};
}

enum class FolderKind { None, Dataset, Evaluation, Prediction, Reconstruction, Sequence };

FolderKind folderKind(const fs::path& folder) {
  if (isFormat(folder / "manifest.json", "pixelcloth.dataset")) return FolderKind::Dataset;
  if (fs::is_regular_file(folder / "prediction.json")) return FolderKind::Prediction;
  if (fs::is_regular_file(folder / "garment.pc2") && fs::is_regular_file(folder / "metrics.json"))
    return FolderKind::Sequence;
  if (fs::is_regular_file(folder / "predictions.npy") && fs::is_regular_file(folder / "metrics.json"))
    return FolderKind::Evaluation;
  if (fs::is_regular_file(folder / "metrics.json") && fs::is_regular_file(folder / "length_model.json"))
    return FolderKind::Reconstruction;
  return FolderKind::None;
}

std::vector<ViewScene> scenesOf(const fs::path& folder, FolderKind kind, const std::string& group,
                                const ViewOptions& options) {
  switch (kind) {
    case FolderKind::Dataset:
      return datasetScenes(folder, group, options);
    case FolderKind::Evaluation:
      return evaluationScenes(folder, group, options);
    case FolderKind::Prediction:
      return predictionScenes(folder, group);
    case FolderKind::Reconstruction:
      return reconstructionScenes(folder, group);
    case FolderKind::Sequence:
      return sequenceScenes(folder, group);
    case FolderKind::None:
      break;
  }
  return {};
}

const char* kindName(FolderKind kind) {
  switch (kind) {
    case FolderKind::Dataset:
      return "dataset";
    case FolderKind::Evaluation:
      return "evaluation";
    case FolderKind::Prediction:
      return "prediction";
    case FolderKind::Reconstruction:
      return "reconstruction";
    case FolderKind::Sequence:
      return "sequence";
    case FolderKind::None:
      break;
  }
  return "folder";
}

/// The viewable folders under `folder`, three levels deep, in path order; a viewable folder's own sub-folders are
/// not searched (a dataset's garment/, a reconstruction's samples).
void findViewable(const fs::path& folder, int depth, std::vector<std::pair<fs::path, FolderKind>>& found) {
  std::vector<fs::path> children;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    if (entry.is_directory() && !entry.is_symlink()) children.push_back(entry.path());
  std::sort(children.begin(), children.end());
  for (const fs::path& child : children) {
    const FolderKind kind = folderKind(child);
    if (kind != FolderKind::None)
      found.emplace_back(child, kind);
    else if (depth > 1)
      findViewable(child, depth - 1, found);
  }
}

}  // namespace

ViewSite viewFolder(const fs::path& folder, const ViewOptions& options) {
  PIXELCLOTH_CHECK(fs::is_directory(folder), "view: " << folder.string()
                                                      << " is not a folder (expected an output "
                                                         "folder of pixelcloth)");
  PIXELCLOTH_CHECK(options.maxScenes >= 1, "view --max-scenes " << options.maxScenes << ": expected at least 1");
  ViewSite site;
  site.source = fs::absolute(folder).lexically_normal().string();
  const std::string name = folderName(folder);
  const FolderKind kind = folderKind(folder);
  if (kind != FolderKind::None) {
    site.title = std::string(kindName(kind)) + " " + name;
    site.scenes = scenesOf(folder, kind, kindName(kind), options);
    return site;
  }
  // A folder of outputs, as the demo's report: each viewable sub-folder as one group, a few scenes each.
  std::vector<std::pair<fs::path, FolderKind>> found;
  findViewable(folder, 3, found);
  PIXELCLOTH_CHECK(!found.empty(),
                   "view: " << folder.string()
                            << " holds no output pixelcloth can show (expected a dataset, or the folder of evaluate, "
                               "predict, reconstruct --dataset, predict --motion or reconstruct --markers-sequence, "
                               "or a folder holding such folders)");
  ViewOptions each = options;
  each.maxScenes = std::min(options.maxScenes, 4);
  site.title = "outputs in " + name;
  for (const auto& [path, childKind] : found) {
    const std::string group = fs::relative(path, folder).string() + " (" + kindName(childKind) + ")";
    for (ViewScene& scene : scenesOf(path, childKind, group, each)) site.scenes.push_back(std::move(scene));
  }
  return site;
}

}  // namespace pixelcloth::viz
