// Garments from sparse markers (DESIGN.md, "Key-point-to-cage spline solver"): spline cage -> offsets -> procedural
// patch fill -> positions; and the evaluation of every method on a dataset split.
#include "pixelcloth/recon/reconstruct.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <mutex>
#include <sstream>

#include "dataset_internal.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/mesh_index.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/patches/frame.h"
#include "pixelcloth/patches/garment_fill.h"
#include "pixelcloth/patches/patch.h"

namespace pixelcloth::recon {

namespace fs = std::filesystem;

namespace {
const core::EnumNames<ReconstructionMethod, 4> kMethods{
    "reconstruction method",
    {{{ReconstructionMethod::Linear, "linear"},
      {ReconstructionMethod::CatmullRom, "catmull_rom"},
      {ReconstructionMethod::Spline, "spline"},
      {ReconstructionMethod::SplineAnisotropic, "spline_anisotropic"}}}};
}  // namespace

const char* reconstructionMethodName(ReconstructionMethod method) { return kMethods.name(method); }

std::vector<ReconstructionMethod> allReconstructionMethods() { return kMethods.values(); }

ReconstructionMethod reconstructionMethodFromName(const std::string& name, const std::string& context) {
  return kMethods.fromName(name, context);
}

void ReconstructionOptions::validate() const {
  spline.validate();
  anisotropic.validate();
  PIXELCLOTH_CHECK(std::isfinite(bodyClearance) && bodyClearance <= 0.05,
                   "reconstruct: body clearance " << bodyClearance << " m, expected at most 0.05 (< 0: off)");
}

// ---------------------------------------------------------------------------------------------------------------------
// PosedBody

struct PosedBody::Impl {
  core::MeshIndex index;
  garment::EmbeddedFrames frames;
};

PosedBody::PosedBody(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, garment::EmbeddedFrames frames)
    : impl_(std::make_unique<Impl>(Impl{core::MeshIndex(vertices, faces), std::move(frames)})) {}

PosedBody::~PosedBody() = default;
PosedBody::PosedBody(PosedBody&&) noexcept = default;

const garment::EmbeddedFrames& PosedBody::frames() const { return impl_->frames; }

int PosedBody::pushOut(Eigen::MatrixX3d& points, double clearance) const {
  int moved = 0;
  for (int i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i).transpose();
    const core::MeshHit hit = impl_->index.closest(p);
    const Eigen::Vector3d normal = impl_->index.smoothNormal(hit.face, hit.barycentric);
    // Inside when behind the smooth normal; outside, the clearance is measured from the closest point outwards.
    const Eigen::Vector3d away = p - hit.point;
    const bool inside = away.dot(normal) < 0;
    if (inside || away.norm() < clearance) {
      const Eigen::Vector3d direction = inside || away.norm() < 1e-12 ? normal : Eigen::Vector3d(away.normalized());
      points.row(i) = (hit.point + clearance * direction).transpose();
      ++moved;
    }
  }
  return moved;
}

void DatasetReconstructionOptions::validate() const {
  markers.validate();
  capture.validate();
  reconstruction.validate();
  PIXELCLOTH_CHECK(meshes >= 0, "reconstruct: meshes " << meshes << ", expected >= 0");
  PIXELCLOTH_CHECK(lengthModel.kind != LengthModelSource::Kind::File || !lengthModel.file.empty(),
                   "reconstruct: the length model file is empty");
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
  body::Body body;
  garment::Garment garment;
  garment::Embedding embedding;
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

GarmentReconstructor::GarmentReconstructor(const body::Body& body, const garment::Garment& garment,
                                           const garment::Embedding& embedding, const Eigen::MatrixX3d& restPositions,
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

const garment::Garment& GarmentReconstructor::garment() const { return impl_->garment; }
const cage::Cage& GarmentReconstructor::cage() const { return impl_->cage; }
const cage::CageSplineSolver& GarmentReconstructor::solver() const { return *impl_->solver; }

PosedBody GarmentReconstructor::posed(const body::Pose& pose) const {
  const Eigen::MatrixX3d vertices = impl_->body.posedVertices(pose);
  return PosedBody(vertices, impl_->body.mesh.F,
                   garment::embeddedFrames(vertices, impl_->body.mesh.F, impl_->embedding));
}

Reconstruction GarmentReconstructor::fillFromCage(const Eigen::MatrixX3d& cagePositions, const PosedBody& body,
                                                  bool anisotropic) const {
  const garment::EmbeddedFrames& frames = body.frames();
  const int V = impl_->garment.mesh.numVertices();
  PIXELCLOTH_CHECK(cagePositions.rows() == V && frames.origin.rows() == V,
                   "reconstruct: " << cagePositions.rows() << " cage positions and " << frames.origin.rows()
                                   << " frames for " << V << " cloth pixels");
  Reconstruction result;
  result.cage = cagePositions;
  // Only cage rows are meaningful; the others are overwritten by the fill, so give them a harmless value.
  Eigen::MatrixX3d known = frames.origin;
  for (int v : impl_->solver->cageVertices()) known.row(v) = cagePositions.row(v);
  const Eigen::MatrixX3d cageOffsets = garment::offsetsFromPositions(frames, known);
  result.offsets = impl_->fill(anisotropic).fill(cageOffsets);
  result.positions = garment::positionsFromOffsets(frames, result.offsets);
  if (impl_->options.bodyClearance >= 0) {
    result.pushedOut = body.pushOut(result.positions, impl_->options.bodyClearance);
    if (result.pushedOut > 0) result.offsets = garment::offsetsFromPositions(frames, result.positions);
  }
  return result;
}

Reconstruction GarmentReconstructor::reconstruct(const cage::MarkerSet& markers, const PosedBody& body,
                                                 ReconstructionMethod method, const std::string& context) const {
  const Eigen::MatrixX3d& rest = body.frames().origin;
  for (const cage::Marker& m : markers.markers) {
    PIXELCLOTH_CHECK(m.vertex >= 0 && m.vertex < rest.rows(),
                     context << ": marker '" << m.name << "' is on vertex " << m.vertex << ", the " << impl_->garment.name
                             << " has " << rest.rows());
    const double distance = (m.position - rest.row(m.vertex).transpose()).norm();
    PIXELCLOTH_CHECK(distance <= kMaxMarkerDistance,
                     context << ": marker '" << m.name << "' is " << distance
                             << " m from where its garment vertex rests on the posed body; expected within "
                             << kMaxMarkerDistance << " m (markers in other units than metres, or of another pose?)");
  }
  const cage::CageFit fit = impl_->solver->solve(markers, curveMethodOf(method));
  Reconstruction result = fillFromCage(fit.positions, body, method == ReconstructionMethod::SplineAnisotropic);
  result.spline = fit.summary;
  return result;
}

Reconstruction GarmentReconstructor::reconstruct(const cage::MarkerSet& markers, const body::Pose& pose,
                                                 ReconstructionMethod method, const std::string& context) const {
  markers.validate(impl_->garment, impl_->cage, context, true);
  return reconstruct(markers, posed(pose), method, context);
}

// ---------------------------------------------------------------------------------------------------------------------
// Evaluation on a dataset

namespace detail {

std::unique_ptr<GarmentReconstructor> datasetReconstructor(const data::Dataset& dataset,
                                                           const ReconstructionOptions& options) {
  const data::DatasetFolder folder = dataset.info.where();
  const garment::Garment garment = data::datasetGarment(dataset.info);
  const body::Body body = data::loadDatasetBody(folder);
  const garment::Embedding embedding = data::loadDatasetEmbedding(folder, body.mesh.numFaces());
  const Eigen::MatrixX3d rest = data::loadDatasetRestPositions(folder, garment.mesh.numVertices());
  return std::make_unique<GarmentReconstructor>(body, garment, embedding, rest, options);
}

body::Pose poseOfRow(const data::Dataset& dataset, int row) {
  return body::Pose::fromLeading(dataset.pose(row), dataset.info.folder.string() + ": pose " + std::to_string(row));
}

cage::MarkerSet captureMarkers(const cage::MarkerSet& definition, const Eigen::MatrixX3d& truth,
                               const cage::CaptureOptions& capture, int index) {
  cage::CaptureOptions seeded = capture;
  seeded.seed = capture.seed * 1000003ULL + static_cast<std::uint64_t>(index);
  return cage::placeMarkers(definition, truth, seeded);
}

nlohmann::json useLengthModel(GarmentReconstructor& reconstructor, const data::Dataset& dataset,
                              const cage::MarkerSet& definition, const LengthModelSource& lengthModel,
                              double markerSpacing, const cage::LengthModelOptions& fit) {
  const std::string datasetName = dataset.info.folder.string();
  if (lengthModel.kind == LengthModelSource::Kind::None) {
    reconstructor.setLengthModel(std::nullopt);
    return "none";
  }
  if (lengthModel.kind == LengthModelSource::Kind::Fit) {
    const std::vector<int> train = dataset.rowsOf(data::Split::Train);
    if (train.empty()) {
      PIXELCLOTH_INFO("reconstruct: " << datasetName
                                      << " has no training samples to fit the spline's length model on; the "
                                         "spline keeps rest lengths");
      reconstructor.setLengthModel(std::nullopt);
      return "none";
    }
    std::vector<Eigen::MatrixX3d> samples;
    for (int r : train) samples.push_back(dataset.positionsOf(r).cast<double>());
    const cage::LengthModel model = reconstructor.solver().fitLengthModel(definition, samples, markerSpacing, fit);
    reconstructor.setLengthModel(model);
    return {{"source", "fitted on the train split"}, {"samples", model.samples}};
  }
  const std::string file = lengthModel.file.string();
  const cage::LengthModel model = cage::readLengthModel(lengthModel.file);
  PIXELCLOTH_CHECK(std::abs(model.markerSpacing - markerSpacing) < 1e-9,
                   file << ": fitted for markers " << model.markerSpacing << " m apart, these are " << markerSpacing
                        << " m apart; fit one at this spacing (reconstruct --dataset with "
                           "--length-model fit writes length_model.json)");
  reconstructor.setLengthModel(model, file);
  return {{"source", fs::absolute(lengthModel.file).string()}, {"samples", model.samples}};
}

}  // namespace detail

namespace {
std::string sampleFolder(int index) {
  std::ostringstream s;
  s << "sample_" << std::setw(6) << std::setfill('0') << index;
  return s.str();
}
}  // namespace

DatasetReconstructionReport reconstructDataset(const data::DatasetFolder& where, const fs::path& out,
                                               const DatasetReconstructionOptions& options) {
  const fs::path& datasetFolder = where.path;
  options.validate();
  core::checkOutputFolder(out);
  const data::Dataset dataset = data::openDataset(where);
  std::vector<int> rows;
  for (int r = 0; r < dataset.rows(); ++r)
    if (!options.split || dataset.split[r] == static_cast<std::uint8_t>(*options.split)) rows.push_back(r);
  const std::string splitLabel = options.split ? data::splitName(*options.split) : "all";
  PIXELCLOTH_CHECK(!rows.empty(), datasetFolder.string() << ": the " << splitLabel << " split has no samples ("
                                                         << dataset.rows() << " in the folder); try --split all");
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<GarmentReconstructor> made = detail::datasetReconstructor(dataset, options.reconstruction);
  GarmentReconstructor& reconstructor = *made;
  const garment::Garment& garment = reconstructor.garment();
  const cage::Cage& cage = reconstructor.cage();
  const cage::MarkerSet definition = cage::defineMarkers(garment, cage, options.markers);
  const nlohmann::json lengthModelJson = detail::useLengthModel(reconstructor, dataset, definition, options.lengthModel,
                                                                options.markers.spacing, options.lengthModelFit);
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
    const cage::MarkerSet markers = detail::captureMarkers(definition, truth, options.capture, index);
    const PosedBody posed = reconstructor.posed(detail::poseOfRow(dataset, r));
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
      {"split", splitLabel},
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

  cage::writeMarkers(out / "markers.json", definition);
  if (reconstructor.solver().lengthModel())
    cage::writeLengthModel(out / "length_model.json", *reconstructor.solver().lengthModel());
  core::writeJson(out / "metrics.json", report.metrics);
  PIXELCLOTH_INFO("reconstruct: " << report.samples << " samples of " << datasetFolder.string() << " (" << splitLabel
                                  << ") in " << seconds << " s -> " << out.string());
  return report;
}

}  // namespace pixelcloth::recon
