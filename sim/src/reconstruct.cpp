// Garments from sparse markers (issue 5): spline cage -> offsets -> procedural patch fill -> positions; and the
// evaluation of every method on a dataset split.
#include "pixelcloth/sim/reconstruct.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <mutex>
#include <sstream>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/core/render.h"
#include "pixelcloth/patches/frame.h"
#include "pixelcloth/patches/garment_fill.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/sim/dataset.h"

namespace pixelcloth::sim {

namespace fs = std::filesystem;

const char* reconstructionMethodName(ReconstructionMethod method) {
  switch (method) {
    case ReconstructionMethod::Linear:
      return "linear";
    case ReconstructionMethod::CatmullRom:
      return "catmull_rom";
    case ReconstructionMethod::Spline:
      return "spline";
    case ReconstructionMethod::SplineAnisotropic:
      return "spline_anisotropic";
  }
  return "spline";
}

std::vector<ReconstructionMethod> allReconstructionMethods() {
  return {ReconstructionMethod::Linear, ReconstructionMethod::CatmullRom, ReconstructionMethod::Spline,
          ReconstructionMethod::SplineAnisotropic};
}

ReconstructionMethod reconstructionMethodFromName(const std::string& name, const std::string& context) {
  for (ReconstructionMethod m : allReconstructionMethods())
    if (name == reconstructionMethodName(m)) return m;
  PIXELCLOTH_FAIL(context << ": unknown method '" << name
                          << "'; expected linear, catmull_rom, spline or spline_anisotropic");
}

void ReconstructionOptions::validate() const {
  spline.validate();
  anisotropic.validate();
  PIXELCLOTH_CHECK(std::isfinite(bodyClearance) && bodyClearance <= 0.05,
                   "reconstruct: body clearance " << bodyClearance << " m, expected at most 0.05 (< 0: off)");
}

// ---------------------------------------------------------------------------------------------------------------------
// PosedBody

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>>>;
}  // namespace

struct PosedBody::Impl {
  Eigen::MatrixX3d V, vertexNormals;
  Eigen::MatrixX3i F;
  core::EmbeddedFrames frames;
  std::vector<Triangle> triangles;
  std::unique_ptr<Tree> tree;
};

PosedBody::PosedBody(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, core::EmbeddedFrames frames)
    : impl_(std::make_unique<Impl>()) {
  impl_->V = vertices;
  impl_->F = faces;
  impl_->vertexNormals = core::vertexNormals(vertices, faces);
  impl_->frames = std::move(frames);
  impl_->triangles.reserve(faces.rows());
  auto point = [&](int v) { return Point(vertices(v, 0), vertices(v, 1), vertices(v, 2)); };
  for (int f = 0; f < faces.rows(); ++f)
    impl_->triangles.emplace_back(point(faces(f, 0)), point(faces(f, 1)), point(faces(f, 2)));
  impl_->tree = std::make_unique<Tree>(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree->accelerate_distance_queries();
}

PosedBody::~PosedBody() = default;
PosedBody::PosedBody(PosedBody&&) noexcept = default;

const core::EmbeddedFrames& PosedBody::frames() const { return impl_->frames; }

int PosedBody::pushOut(Eigen::MatrixX3d& points, double clearance) const {
  int moved = 0;
  for (int i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i).transpose();
    const auto [closest, triangle] = impl_->tree->closest_point_and_primitive(Point(p.x(), p.y(), p.z()));
    const int f = static_cast<int>(triangle - impl_->triangles.cbegin());
    const Eigen::Vector3d q(closest.x(), closest.y(), closest.z());
    // The smooth normal there: the vertex normals blended by the closest point's barycentric coordinates.
    const Eigen::Vector3d a = impl_->V.row(impl_->F(f, 0)), b = impl_->V.row(impl_->F(f, 1)),
                          c = impl_->V.row(impl_->F(f, 2));
    const double area = (b - a).cross(c - a).norm();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = impl_->V.row(impl_->F(f, (k + 1) % 3)), w = impl_->V.row(impl_->F(f, (k + 2) % 3));
      const double weight = area > 0 ? (u - q).cross(w - q).norm() / area : 1.0 / 3;
      normal += weight * impl_->vertexNormals.row(impl_->F(f, k)).transpose();
    }
    normal.normalize();
    // Inside when behind the smooth normal; outside, the clearance is measured from the closest point outwards.
    const Eigen::Vector3d away = p - q;
    const bool inside = away.dot(normal) < 0;
    if (inside || away.norm() < clearance) {
      const Eigen::Vector3d direction = inside || away.norm() < 1e-12 ? normal : Eigen::Vector3d(away.normalized());
      points.row(i) = (q + clearance * direction).transpose();
      ++moved;
    }
  }
  return moved;
}

void DatasetReconstructionOptions::validate() const {
  PIXELCLOTH_CHECK(split == "train" || split == "regularisation" || split == "test" || split == "all",
                   "reconstruct: split '" << split << "', expected train, regularisation, test or all");
  markers.validate();
  capture.validate();
  reconstruction.validate();
  PIXELCLOTH_CHECK(meshes >= 0, "reconstruct: meshes " << meshes << ", expected >= 0");
  PIXELCLOTH_CHECK(!lengthModel.empty(), "reconstruct: the length model is empty; expected fit, none or a file");
  lengthModelFit.validate();
}

// ---------------------------------------------------------------------------------------------------------------------
// GarmentReconstructor

namespace {
cage::CurveMethod curveMethodOf(ReconstructionMethod method) {
  switch (method) {
    case ReconstructionMethod::Linear:
      return cage::CurveMethod::Linear;
    case ReconstructionMethod::CatmullRom:
      return cage::CurveMethod::CatmullRom;
    default:
      return cage::CurveMethod::Spline;
  }
}
}  // namespace

struct GarmentReconstructor::Impl {
  core::Body body;
  core::Garment garment;
  core::Embedding embedding;
  ReconstructionOptions options;
  cage::Cage cage;
  std::vector<patches::Patch> patches;
  std::unique_ptr<cage::CageSplineSolver> solver;
  mutable std::mutex fillMutex;
  mutable std::unique_ptr<patches::GarmentFill> isotropic, anisotropic;

  const patches::GarmentFill& fill(bool aniso) const {
    std::lock_guard<std::mutex> lock(fillMutex);
    std::unique_ptr<patches::GarmentFill>& slot = aniso ? anisotropic : isotropic;
    if (!slot)
      slot = std::make_unique<patches::GarmentFill>(garment, patches,
                                                    aniso ? options.anisotropic : patches::BasisOptions{});
    return *slot;
  }
};

GarmentReconstructor::GarmentReconstructor(const core::Body& body, const core::Garment& garment,
                                           const core::Embedding& embedding, const Eigen::MatrixX3d& restPositions,
                                           const ReconstructionOptions& options)
    : impl_(std::make_unique<Impl>()) {
  options.validate();
  PIXELCLOTH_CHECK(embedding.size() == garment.mesh.numVertices(),
                   "reconstruct: the embedding has " << embedding.size() << " cloth pixels, the " << garment.name
                                                     << " has " << garment.mesh.numVertices() << " vertices");
  embedding.validate(body.mesh.numFaces(), "reconstruct: embedding");
  impl_->body = body;
  impl_->garment = garment;
  impl_->embedding = embedding;
  impl_->options = options;
  impl_->cage = cage::garmentCage(garment);
  impl_->patches = patches::segmentPatches(garment, cage::cutEdges(impl_->cage));
  impl_->solver = std::make_unique<cage::CageSplineSolver>(impl_->garment, impl_->cage, restPositions, options.spline);
  impl_->solver->setLengthModel(options.lengthModel);
}

void GarmentReconstructor::setLengthModel(std::optional<cage::LengthModel> model, const std::string& context) {
  impl_->solver->setLengthModel(std::move(model), context);
}

GarmentReconstructor::~GarmentReconstructor() = default;

const core::Garment& GarmentReconstructor::garment() const { return impl_->garment; }
const cage::Cage& GarmentReconstructor::cage() const { return impl_->cage; }
const cage::CageSplineSolver& GarmentReconstructor::solver() const { return *impl_->solver; }

PosedBody GarmentReconstructor::posed(const core::Pose& pose) const {
  const Eigen::MatrixX3d vertices = impl_->body.posedVertices(pose);
  return PosedBody(vertices, impl_->body.mesh.F, core::embeddedFrames(vertices, impl_->body.mesh.F, impl_->embedding));
}

Reconstruction GarmentReconstructor::fillFromCage(const Eigen::MatrixX3d& cagePositions, const PosedBody& body,
                                                  bool anisotropic) const {
  const core::EmbeddedFrames& frames = body.frames();
  const int V = impl_->garment.mesh.numVertices();
  PIXELCLOTH_CHECK(cagePositions.rows() == V && frames.origin.rows() == V,
                   "reconstruct: " << cagePositions.rows() << " cage positions and " << frames.origin.rows()
                                   << " frames for " << V << " cloth pixels");
  Reconstruction result;
  result.cage = cagePositions;
  // Only cage rows are meaningful; the others are overwritten by the fill, so give them a harmless value.
  Eigen::MatrixX3d known = frames.origin;
  for (int v : impl_->solver->cageVertices()) known.row(v) = cagePositions.row(v);
  const Eigen::MatrixX3d cageOffsets = core::offsetsFromPositions(frames, known);
  result.offsets = impl_->fill(anisotropic).fill(cageOffsets);
  result.positions = core::positionsFromOffsets(frames, result.offsets);
  if (impl_->options.bodyClearance >= 0) {
    result.pushedOut = body.pushOut(result.positions, impl_->options.bodyClearance);
    if (result.pushedOut > 0) result.offsets = core::offsetsFromPositions(frames, result.positions);
  }
  return result;
}

Reconstruction GarmentReconstructor::reconstruct(const cage::MarkerSet& markers, const PosedBody& body,
                                                 ReconstructionMethod method) const {
  const cage::CageFit fit = impl_->solver->solve(markers, curveMethodOf(method));
  Reconstruction result = fillFromCage(fit.positions, body, method == ReconstructionMethod::SplineAnisotropic);
  result.spline = fit.summary;
  return result;
}

Reconstruction GarmentReconstructor::reconstruct(const cage::MarkerSet& markers, const core::Pose& pose,
                                                 ReconstructionMethod method) const {
  markers.validate(impl_->garment, impl_->cage, "markers", true);
  return reconstruct(markers, posed(pose), method);
}

// ---------------------------------------------------------------------------------------------------------------------
// Pictures

core::RgbImage renderPatternValues(const core::Garment& garment, const Eigen::VectorXd& values, double maxValue,
                                   const std::string& title, int size) {
  PIXELCLOTH_CHECK(values.size() == garment.mesh.numVertices(),
                   "pattern picture: " << values.size() << " values for " << garment.mesh.numVertices() << " vertices");
  const int titleHeight = 24, gap = 8, layouts = garment.numLayouts();
  core::RgbImage image(layouts * size + (layouts - 1) * gap, size + titleHeight);
  core::drawText(image, {6, 6}, title, {0, 0, 0}, core::textExtent(title, 2).x() + 12 <= image.width ? 2 : 1);
  const double scale = maxValue > 0 ? maxValue : 1;
  for (int l = 0; l < layouts; ++l) {
    const patches::ImageFrame frame = patches::layoutFrame(garment, l, size);
    const int x0 = l * (size + gap);
    for (int f = 0; f < garment.mesh.numFaces(); ++f) {
      if (garment.faceLayout[f] != l) continue;
      double mean = 0;
      Eigen::Vector2d corner[3];
      for (int k = 0; k < 3; ++k) {
        mean += values[garment.mesh.F(f, k)] / 3;
        corner[k] =
            frame.toPixel(garment.mesh.UV.row(garment.mesh.FUV(f, k)).transpose()) + Eigen::Vector2d(x0, titleHeight);
      }
      const Eigen::Vector3d c = core::colorRamp(std::clamp(mean / scale, 0.0, 1.0));
      core::fillTriangle(image, corner[0], corner[1], corner[2],
                         {static_cast<std::uint8_t>(255 * c.x()), static_cast<std::uint8_t>(255 * c.y()),
                          static_cast<std::uint8_t>(255 * c.z())});
    }
    core::drawText(image, {x0 + 6, titleHeight + size - 14}, garment.layouts[l], {90, 90, 90}, 1);
  }
  return image;
}

// ---------------------------------------------------------------------------------------------------------------------
// Evaluation on a dataset

namespace {
core::Pose poseOfRow(const Dataset& dataset, int row) {
  return core::Pose::fromLeading(dataset.pose(row), dataset.info.folder.string() + ": pose " + std::to_string(row));
}

std::string sampleFolder(int index) {
  std::ostringstream s;
  s << "sample_" << std::setw(6) << std::setfill('0') << index;
  return s.str();
}
}  // namespace

DatasetReconstructionReport reconstructDataset(const fs::path& datasetFolder, const fs::path& out,
                                               const DatasetReconstructionOptions& options) {
  options.validate();
  core::checkOutputFolder(out);
  const Dataset dataset = openDataset(datasetFolder);
  std::vector<int> rows;
  for (int r = 0; r < dataset.rows(); ++r)
    if (options.split == "all" || options.split == splitName(static_cast<Split>(dataset.split[r]))) rows.push_back(r);
  PIXELCLOTH_CHECK(!rows.empty(), datasetFolder.string() << ": the " << options.split << " split has no samples ("
                                                         << dataset.rows() << " in the folder); try --split all");
  const core::Garment garment = datasetGarment(dataset.info);
  const core::Body body = loadDatasetBody(datasetFolder);
  const core::Embedding embedding = loadDatasetEmbedding(datasetFolder, body.mesh.numFaces());
  const Eigen::MatrixX3d rest = loadDatasetRestPositions(datasetFolder, garment.mesh.numVertices());
  const auto start = std::chrono::steady_clock::now();
  GarmentReconstructor reconstructor(body, garment, embedding, rest, options.reconstruction);
  const cage::Cage& cage = reconstructor.cage();
  const cage::MarkerSet definition = cage::defineMarkers(garment, cage, options.markers);
  nlohmann::json lengthModelJson = "none";
  if (options.lengthModel == "fit") {
    const std::vector<int> train = dataset.rowsOf(Split::Train);
    if (train.empty()) {
      PIXELCLOTH_INFO("reconstruct: " << datasetFolder.string()
                                      << " has no training samples to fit the spline's length model on; the "
                                         "spline keeps rest lengths");
      reconstructor.setLengthModel(std::nullopt);
    } else {
      std::vector<Eigen::MatrixX3d> samples;
      for (int r : train) samples.push_back(dataset.positionsOf(r).cast<double>());
      const cage::LengthModel model =
          reconstructor.solver().fitLengthModel(definition, samples, options.markers.spacing, options.lengthModelFit);
      reconstructor.setLengthModel(model);
      lengthModelJson = {{"source", "fitted on the train split"}, {"samples", model.samples}};
    }
  } else if (options.lengthModel == "none") {
    reconstructor.setLengthModel(std::nullopt);
  } else {
    const cage::LengthModel model = cage::readLengthModel(options.lengthModel);
    PIXELCLOTH_CHECK(std::abs(model.markerSpacing - options.markers.spacing) < 1e-9,
                     options.lengthModel << ": fitted for markers " << model.markerSpacing << " m apart, these are "
                                         << options.markers.spacing
                                         << " m apart; fit one at this spacing (reconstruct --dataset with "
                                            "--length-model fit writes length_model.json)");
    reconstructor.setLengthModel(model, options.lengthModel);
    lengthModelJson = {{"source", fs::absolute(options.lengthModel).string()}, {"samples", model.samples}};
  }
  const std::vector<int>& cageVertices = reconstructor.solver().cageVertices();
  const std::vector<ReconstructionMethod> methods = allReconstructionMethods();
  const int V = garment.mesh.numVertices(), M = static_cast<int>(methods.size());
  const int C = static_cast<int>(cage.curves.size());

  std::vector<double> cageSum(M, 0), garmentSum(M, 0), garmentMax(M, 0), pushedSum(M, 0);
  std::vector<std::vector<double>> curveSum(M, std::vector<double>(C, 0)), curveRel(M, std::vector<double>(C, 0)),
      curvePosition(M, std::vector<double>(C, 0));
  std::vector<Eigen::VectorXd> vertexSum(M, Eigen::VectorXd::Zero(V));
  std::vector<double> spline(2, 0);  // iterations, max length error
  core::Progress progress("reconstruct", static_cast<std::int64_t>(rows.size()));
  int written = 0;
  for (int r : rows) {
    const int index = dataset.info.settings.first() + r;
    const Eigen::MatrixX3d truth = dataset.positionsOf(r).cast<double>();
    cage::CaptureOptions capture = options.capture;
    capture.seed = options.capture.seed * 1000003ULL + static_cast<std::uint64_t>(index);
    const cage::MarkerSet markers = cage::placeMarkers(definition, truth, capture);
    const PosedBody posed = reconstructor.posed(poseOfRow(dataset, r));
    const bool writeMeshes = written < options.meshes;
    if (writeMeshes) {
      core::Mesh mesh = garment.mesh;
      mesh.V = truth;
      core::writeMesh(out / sampleFolder(index) / "truth.obj", mesh);
    }
    for (int m = 0; m < M; ++m) {
      const Reconstruction rec = reconstructor.reconstruct(markers, posed, methods[m]);
      const Eigen::VectorXd error = (rec.positions - truth).rowwise().norm();
      vertexSum[m] += error;
      garmentSum[m] += error.mean();
      garmentMax[m] = std::max(garmentMax[m], error.maxCoeff());
      pushedSum[m] += static_cast<double>(rec.pushedOut) / V;
      double cageError = 0;
      for (int v : cageVertices) cageError += (rec.cage.row(v) - truth.row(v)).norm();
      cageSum[m] += cageError / cageVertices.size();
      for (int c = 0; c < C; ++c) {
        const double truthLength = cage::curvePolylineLength(truth, cage.curves[c]);
        const double difference = std::abs(cage::curvePolylineLength(rec.cage, cage.curves[c]) - truthLength);
        curveSum[m][c] += difference;
        curveRel[m][c] += difference / truthLength;
        double position = 0;
        for (int v : cage.curves[c].vertices) position += (rec.cage.row(v) - truth.row(v)).norm();
        curvePosition[m][c] += position / cage.curves[c].vertices.size();
      }
      if (methods[m] == ReconstructionMethod::Spline) {
        spline[0] += rec.spline.iterations;
        spline[1] = std::max(spline[1], rec.spline.maxLengthError);
      }
      if (writeMeshes) {
        core::Mesh mesh = garment.mesh;
        mesh.V = rec.positions;
        core::writeMesh(out / sampleFolder(index) / (std::string(reconstructionMethodName(methods[m])) + ".obj"), mesh);
      }
    }
    written += writeMeshes ? 1 : 0;
    progress.advance();
  }
  progress.finish();
  const double n = static_cast<double>(rows.size());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  DatasetReconstructionReport report;
  report.samples = static_cast<int>(rows.size());
  nlohmann::json methodsJson = nlohmann::json::object();
  for (int m = 0; m < M; ++m) {
    nlohmann::json curves = nlohmann::json::object();
    double curveMean = 0;
    for (int c = 0; c < C; ++c) {
      curves[cage.curves[c].name] = {{"position_error_cm", 100 * curvePosition[m][c] / n},
                                     {"length_error_cm", 100 * curveSum[m][c] / n},
                                     {"length_error_percent", 100 * curveRel[m][c] / n}};
      curveMean += 100 * curveSum[m][c] / n / C;
    }
    methodsJson[reconstructionMethodName(methods[m])] = {
        {"cage_cm", 100 * cageSum[m] / n},       {"garment_cm", 100 * garmentSum[m] / n},
        {"max_garment_cm", 100 * garmentMax[m]}, {"pushed_out_percent", 100 * pushedSum[m] / n},
        {"curve_length_error_cm", curveMean},    {"curves", curves}};
    report.meanVertexError.push_back(vertexSum[m] / n);
  }
  report.metrics = {
      {"dataset", fs::absolute(datasetFolder).string()},
      {"garment", garment.name},
      {"split", options.split},
      {"samples", report.samples},
      {"markers", definition.markers.size()},
      {"marker_spacing_m", options.markers.spacing},
      {"noise_cm", 100 * options.capture.noise},
      {"dropout", options.capture.dropout},
      {"rest_lengths", cage::restLengthsName(options.reconstruction.spline.restLengths)},
      {"anisotropic",
       {{"theta", options.reconstruction.anisotropic.theta}, {"ratio", options.reconstruction.anisotropic.ratio}}},
      {"length_model", lengthModelJson},
      {"body_clearance_m", options.reconstruction.bodyClearance},
      {"spline_mean_iterations", spline[0] / n},
      {"spline_max_segment_length_error", spline[1]},
      {"seconds", seconds},
      {"methods", methodsJson}};

  // Error maps: every method on one colour scale (the largest mean vertex error of any method, at least 1 cm).
  double scale = 0.01;
  for (const Eigen::VectorXd& e : report.meanVertexError) scale = std::max(scale, e.maxCoeff());
  std::vector<core::RgbImage> maps;
  for (int m = 0; m < M; ++m) {
    std::ostringstream title;
    title << reconstructionMethodName(methods[m]) << " " << std::fixed << std::setprecision(2)
          << 100 * report.meanVertexError[m].mean() << " cm (0-" << std::setprecision(1) << 100 * scale << ")";
    maps.push_back(renderPatternValues(garment, report.meanVertexError[m], scale, title.str()));
  }
  int width = 0, height = 0;
  for (const auto& map : maps) {
    width = std::max(width, map.width);
    height += map.height + 8;
  }
  core::RgbImage sheet(width, height);
  int y = 0;
  for (const auto& map : maps) {
    core::paste(sheet, map, 0, y);
    y += map.height + 8;
  }
  core::writePng(out / "error_maps.png", sheet);
  cage::writeMarkers(out / "markers.json", definition);
  if (reconstructor.solver().lengthModel())
    cage::writeLengthModel(out / "length_model.json", *reconstructor.solver().lengthModel());
  core::writeJson(out / "metrics.json", report.metrics);
  PIXELCLOTH_INFO("reconstruct: " << report.samples << " samples of " << datasetFolder.string() << " (" << options.split
                                  << ") in " << seconds << " s -> " << out.string());
  return report;
}

}  // namespace pixelcloth::sim
