// pixelcloth markers / reconstruct: marker sets on the cage, and garments rebuilt from them (DESIGN.md,
// "Key-point-to-cage spline solver").
#include "pixelcloth/recon/reconstruct.h"

#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/eval/motion_prediction.h"
#include "pixelcloth/motion/motion.h"
#include "pixelcloth/motion/sequence.h"
#include "pixelcloth/motion/trajectories.h"
#include "pixelcloth/recon/base.h"
#include "pixelcloth/viz/motion_pictures.h"
#include "pixelcloth/viz/pictures.h"
#include "prediction_inputs.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
namespace fs = std::filesystem;

struct MarkersArgs {
  std::string garment = "tshirt";
  std::string dataset;
  int sample = 0;
  double spacing = 0.10;
  double noiseCm = 0;
  double dropout = 0;
  std::uint64_t seed = 0;
  std::string out;
  std::string poseOut;
  std::string pc2, trajectories;
};

/// The sequence form of markers: the garment's markers on every frame of a point cache, as trajectories with noise
/// and dropout drawn per frame (seeded by --seed and the frame).
void runMarkersOfSequence(const MarkersArgs& args, const cage::MarkerOptions& options, const garment::Garment& garment,
                          const cage::CaptureOptions& capture) {
  const cage::Cage cage = cage::garmentCage(garment);
  const cage::MarkerSet definition = cage::defineMarkers(garment, cage, options);
  const std::vector<Eigen::MatrixX3f> frames = motion::readPc2(args.pc2);
  PIXELCLOTH_CHECK(frames.front().rows() == garment.mesh.numVertices(),
                   args.pc2 << ": " << frames.front().rows() << " points a frame, expected the "
                            << garment.mesh.numVertices() << " vertices of the " << garment.name);
  std::vector<Eigen::MatrixX3d> positions;
  for (const Eigen::MatrixX3f& frame : frames) positions.push_back(frame.cast<double>());
  const motion::MarkerTrajectories trajectories = eval::markerTrajectories(definition, cage, positions, capture);
  cage::writeMarkers(args.out, definition);
  motion::writeMarkerTrajectories(args.trajectories, trajectories);
  PIXELCLOTH_INFO("markers: " << definition.markers.size() << " markers in " << frames.size() << " frames of "
                              << args.pc2 << " -> " << args.out << ", " << args.trajectories);
}

void runMarkers(const MarkersArgs& args) {
  cage::MarkerOptions options;
  options.spacing = args.spacing;
  options.validate();
  cage::CaptureOptions capture{args.noiseCm / 100, args.dropout, args.seed};
  capture.validate();
  PIXELCLOTH_CHECK(args.pc2.empty() == args.trajectories.empty(),
                   "markers: --pc2 and --trajectories go together (the point cache read, the trajectories written)");
  PIXELCLOTH_CHECK(args.pc2.empty() || args.dataset.empty(), "markers: --pc2 and --dataset exclude each other");
  if (!args.pc2.empty()) {
    const garment::Garment garment = garment::resolveGarment(args.garment, "markers --garment");
    return runMarkersOfSequence(args, options, garment, capture);
  }
  if (args.dataset.empty()) {
    const garment::Garment garment = garment::resolveGarment(args.garment, "markers --garment");
    cage::writeMarkers(args.out, cage::defineMarkers(garment, cage::garmentCage(garment), options));
    PIXELCLOTH_INFO("markers: " << garment.name << " marker definition -> " << args.out);
    return;
  }
  const data::Dataset dataset = data::openDataset(datasetFolder(args.dataset));
  const int row = dataset.info.rowOfSample(args.sample, "markers --sample");
  const garment::Garment garment = data::datasetGarment(dataset.info);
  const cage::MarkerSet definition = cage::defineMarkers(garment, cage::garmentCage(garment), options);
  const cage::MarkerSet markers = cage::placeMarkers(definition, dataset.positionsOf(row).cast<double>(), capture);
  if (!args.poseOut.empty()) {
    core::writeJson(args.poseOut, body::poseToJson(body::Pose::fromLeading(dataset.pose(row), args.dataset)));
  }
  cage::writeMarkers(args.out, markers);
  PIXELCLOTH_INFO("markers: " << markers.markers.size() << " markers of sample " << args.sample << " -> " << args.out);
}

struct ReconstructArgs {
  std::string markers, pose, body, dressing, dataset, split = "test", out, method = "spline", writeBase, garment;
  std::string markersSequence, motion, model, engine = "onednn";
  StitchArgs stitch;
  double noiseCm = 0, dropout = 0, spacing = 0.10;
  std::uint64_t seed = 0;
  int meshes = 3;
  std::string restLengths = "pattern";
  std::string lengthModel;  // markers form: none by default; dataset form: "fit" by default
  double anisoThetaDegrees = 0, anisoRatio = 0.6;
  double bodyClearance = 0.001;
  cage::SplineOptions spline;
  int threads = 0;
  bool quiet = false;
  /// The options of the evaluation alone that were given on the command line (refused with --write-base).
  std::vector<std::string> evaluationOptions;
  /// The options of the markers form alone that were given (refused with --dataset --write-base).
  std::vector<std::string> markersOptions;
};

/// The garment of the markers form: --garment, else the --dressing folder's own (a dataset carries its garment), else
/// the template the marker file names.
garment::Garment markersGarment(const ReconstructArgs& args, const cage::MarkerSet& markers) {
  if (!args.garment.empty()) return garment::resolveGarment(args.garment, "reconstruct --garment");
  const fs::path carried = fs::path(args.dressing) / "garment";
  std::error_code ec;
  if (!args.dressing.empty() && fs::is_regular_file(carried / "garment.json", ec)) return garment::loadGarment(carried);
  try {
    return garment::resolveGarment(markers.garment, args.markers + ": garment");
  } catch (const core::InputError& error) {
    PIXELCLOTH_FAIL(error.what() << "; give the garment folder the markers were defined on with --garment, or a "
                                    "--dressing folder that carries it (a dataset)");
  }
}

/// The body, the dressed garment and its embedding of the markers forms: the --dressing folder's, else the garment
/// dressed on --body or the mannequin.
data::DressingFiles markersDressing(const ReconstructArgs& args, const garment::Garment& garment,
                                    const cage::Cage& cage) {
  if (!args.dressing.empty())
    return data::loadDressingFiles(datasetFolder(args.dressing), garment, "the markers (" + args.markers + ")");
  data::DressingFiles out;
  out.body = args.body.empty() ? body::makeMannequin() : body::loadBody(args.body);
  const cage::Dressing dressing = cage::dressGarment(out.body, cage::bodyCage(out.body), garment, cage);
  out.rest = dressing.relaxed;
  out.embedding = dressing.embedding;
  return out;
}

void runFromMarkers(const ReconstructArgs& args) {
  PIXELCLOTH_CHECK(!args.pose.empty(), "reconstruct --markers needs --pose (the body's pose, JSON)");
  PIXELCLOTH_CHECK(!args.out.empty(), "reconstruct --markers needs --out (the garment's OBJ)");
  PIXELCLOTH_CHECK(args.body.empty() || args.dressing.empty(),
                   "reconstruct: --body and --dressing exclude each other: the dressing folder holds its body");
  const recon::ReconstructionMethod method = recon::reconstructionMethodFromName(args.method, "reconstruct --method");
  recon::ReconstructionOptions options;
  options.spline = args.spline;
  options.spline.restLengths = cage::restLengthsFromName(args.restLengths, "reconstruct --rest-lengths");
  options.bodyClearance = args.bodyClearance;
  // Every input is read and checked before the expensive steps (body, dressing), nothing is written before the end.
  const cage::MarkerSet markers = cage::readMarkers(args.markers);
  PIXELCLOTH_CHECK(args.lengthModel != "fit",
                   "reconstruct --markers --length-model fit: there is no training data to fit on; give the "
                   "length_model.json a dataset run wrote, or none");
  if (!args.lengthModel.empty() && args.lengthModel != "none")
    options.lengthModel = cage::readLengthModel(args.lengthModel);
  const body::Pose pose = body::readPose(args.pose, poseLimits());
  const garment::Garment garment = markersGarment(args, markers);
  const cage::Cage cage = cage::garmentCage(garment);
  markers.validate(garment, cage, args.markers, true);
  const data::DressingFiles dressed = markersDressing(args, garment, cage);
  if (options.lengthModel) options.lengthModel->validate(garment.name, cage, args.lengthModel);
  const recon::GarmentReconstructor reconstructor(dressed.body, garment, dressed.embedding, dressed.rest, options);
  const recon::Reconstruction result = reconstructor.reconstruct(markers, pose, method, args.markers);
  core::Mesh mesh = garment.mesh;
  mesh.V = result.positions;
  core::writeMesh(args.out, mesh);
  PIXELCLOTH_INFO("reconstruct: " << garment.name << " from " << markers.markers.size() << " markers (" << args.method
                                  << "; " << result.spline.summary() << ") -> " << args.out);
}

/// The sequence form: marker trajectories rebuilt frame by frame on the motion's poses, optionally refined by a
/// residual model, written as a garment sequence (eval::writeGarmentSequence).
void runFromMarkerSequence(const ReconstructArgs& args) {
  PIXELCLOTH_CHECK(!args.markers.empty(),
                   "reconstruct --markers-sequence needs --markers (the marker file the "
                   "trajectories' columns follow, e.g. from pixelcloth markers)");
  PIXELCLOTH_CHECK(!args.motion.empty(),
                   "reconstruct --markers-sequence needs --motion (the body's poses of every "
                   "frame, from pixelcloth motion import)");
  PIXELCLOTH_CHECK(args.pose.empty(), "reconstruct --markers-sequence: the poses come from --motion, not --pose");
  PIXELCLOTH_CHECK(!args.out.empty(), "reconstruct --markers-sequence needs --out (the output folder)");
  PIXELCLOTH_CHECK(args.model.empty() || (args.body.empty() && args.dressing.empty() && args.garment.empty()),
                   "reconstruct --model: the model's dataset holds the body and garment; not with --body, --dressing "
                   "or --garment");
  PIXELCLOTH_CHECK(args.body.empty() || args.dressing.empty(),
                   "reconstruct: --body and --dressing exclude each other: the dressing folder holds its body");
  PIXELCLOTH_CHECK(args.stitch.modes.find(',') == std::string::npos,
                   "reconstruct --stitch " << args.stitch.modes << ": one mode");
  core::checkOutputFolder(args.out);
  core::checkRunFolder(args.out, {"metrics.json", {}, "a reconstructed motion"});
  const recon::ReconstructionMethod method = recon::reconstructionMethodFromName(args.method, "reconstruct --method");
  const motion::Motion clip = motion::readMotion(args.motion, poseLimits());
  const cage::MarkerSet definition = cage::readMarkers(args.markers);
  const motion::MarkerTrajectories trajectories =
      motion::readMarkerTrajectories(args.markersSequence, static_cast<int>(definition.markers.size()), args.markers);
  nlohmann::json info = {{"markers", args.markers},
                         {"markers_sequence", args.markersSequence},
                         {"motion", args.motion},
                         {"method", args.model.empty() ? args.method : "spline_anisotropic"},
                         {"model", args.model.empty() ? nlohmann::json() : nlohmann::json(args.model)}};
  eval::MotionPrediction result;
  body::Body body;
  core::Mesh garmentMesh;
  if (!args.model.empty()) {
    // The base of every frame as the model's base folder was made, then the residual networks.
    learn::PredictionInputs inputs = learn::posesPredictionInputs(
        args.model, clip.poses, args.motion, datasetFolder(fs::path()), learn::engineFromName(args.engine, "--engine"));
    PIXELCLOTH_CHECK(inputs.model->residual(), "reconstruct --model " << args.model
                                                                      << ": a model that takes the pose alone; "
                                                                         "for it use predict --motion");
    body = data::loadDatasetBody(inputs.data.info.where());
    garmentMesh = inputs.data.garment.mesh;
    info["dataset"] = fs::absolute(inputs.data.folder).lexically_normal().string();
    const double baseSeconds =
        eval::addTrajectoryBases(inputs, body, definition, args.markers, trajectories, clip, args.threads);
    const std::vector<stitch::Stitcher> stitchers = makeStitchers(args.stitch, inputs);
    result = eval::predictMotion(inputs, stitchers.front(), clip, args.out, info);
    result.predictSeconds += baseSeconds;
  } else {
    const garment::Garment garment = markersGarment(args, definition);
    const cage::Cage cage = cage::garmentCage(garment);
    definition.validate(garment, cage, args.markers, false);
    data::DressingFiles dressed = markersDressing(args, garment, cage);
    body = std::move(dressed.body);
    recon::ReconstructionOptions options;
    options.spline = args.spline;
    options.spline.restLengths = cage::restLengthsFromName(args.restLengths, "reconstruct --rest-lengths");
    options.bodyClearance = args.bodyClearance;
    if (!args.lengthModel.empty() && args.lengthModel != "none") {
      options.lengthModel = cage::readLengthModel(args.lengthModel);
      options.lengthModel->validate(garment.name, cage, args.lengthModel);
    }
    garmentMesh = garment.mesh;
    const std::vector<cage::MarkerSet> captured = eval::capturedFrames(
        definition, cage, trajectories, clip, body.skeleton.positions.row(body.skeleton.index("root")).transpose());
    const recon::GarmentReconstructor reconstructor(body, garment, dressed.embedding, dressed.rest, options);
    const auto start = std::chrono::steady_clock::now();
    std::vector<Eigen::MatrixX3d> garments =
        eval::reconstructFrames(reconstructor, captured, clip.poses, method, args.threads, args.markersSequence);
    result = eval::writeGarmentSequence(body, clip.poses, garmentMesh, std::move(garments), {},
                                        core::secondsSince(start), clip, args.out, info);
  }
  viz::writeSequencePictures(args.out, body.mesh.F, garmentMesh, result);
  std::cout << "reconstruct: " << sequenceSummary(result, args.out) << "\n";
}

/// --length-model of the dataset forms: fit (also when not given), none, or a length model file.
recon::LengthModelSource lengthModelSource(const std::string& text) {
  if (text.empty() || text == "fit") return recon::LengthModelSource::fit();
  if (text == "none") return recon::LengthModelSource::none();
  return recon::LengthModelSource::fromFile(text);
}

/// The reconstruction options of the dataset forms (evaluation and bases).
recon::ReconstructionOptions datasetReconstructionOptions(const ReconstructArgs& args) {
  recon::ReconstructionOptions options;
  options.spline.restLengths = cage::restLengthsFromName(args.restLengths, "reconstruct --rest-lengths");
  // Noisy markers are fitted softly, with the noise as their sigma.
  options.spline.markerSigma = args.noiseCm / 100;
  options.spline.lengthTolerance = args.spline.lengthTolerance;
  options.spline.bendingWeight = args.spline.bendingWeight;
  options.spline.stretch = args.spline.stretch;
  options.spline.tangentPrior = args.spline.tangentPrior;
  options.anisotropic.theta = args.anisoThetaDegrees * M_PI / 180;
  options.anisotropic.ratio = args.anisoRatio;
  options.bodyClearance = args.bodyClearance;
  return options;
}

void runFromDataset(const ReconstructArgs& args) {
  PIXELCLOTH_CHECK(!args.out.empty(),
                   "reconstruct --dataset needs --out (the folder for metrics and meshes), or "
                   "--write-base (a base folder for the learned refinement)");
  core::checkOutputFolder(args.out);
  core::checkRunFolder(args.out, {"metrics.json", {}, "a reconstruction evaluation"});
  recon::DatasetReconstructionOptions options;
  if (args.split == "all")
    options.split.reset();
  else
    options.split = data::splitFromName(args.split, "reconstruct --split");
  options.markers.spacing = args.spacing;
  options.capture = {args.noiseCm / 100, args.dropout, args.seed};
  options.reconstruction = datasetReconstructionOptions(args);
  options.lengthModel = lengthModelSource(args.lengthModel);
  options.meshes = args.meshes;
  const recon::DatasetReconstructionReport report =
      recon::reconstructDataset(datasetFolder(args.dataset), args.out, options);
  core::writePng(std::filesystem::path(args.out) / "error_maps.png",
                 viz::renderReconstructionErrors(
                     data::datasetGarment(data::readDatasetInfo(datasetFolder(args.dataset))), report));
  for (const auto& [name, m] : report.metrics["methods"].items())
    std::cout << name << ": cage " << m["cage_cm"].get<double>() << " cm, garment " << m["garment_cm"].get<double>()
              << " cm\n";
}

void runWriteBase(const ReconstructArgs& args) {
  auto list = [](const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
  };
  PIXELCLOTH_CHECK(args.out.empty(),
                   "reconstruct --write-base and --out exclude each other: --write-base writes the "
                   "base folder, --out the evaluation's metrics and meshes (run twice for both)");
  PIXELCLOTH_CHECK(args.evaluationOptions.empty(),
                   "reconstruct --write-base: " << list(args.evaluationOptions)
                                                << " belong to the evaluation (--out); the base folder holds every "
                                                   "row of the dataset (all splits), rebuilt by spline_anisotropic");
  PIXELCLOTH_CHECK(args.markersOptions.empty(), "reconstruct --write-base: " << list(args.markersOptions)
                                                                             << " belong to the markers form; the "
                                                                                "dataset holds its body and poses");
  core::checkOutputFolder(args.writeBase);
  core::checkRunFolder(args.writeBase, {"manifest.json", {{"format", "pixelcloth.base"}}, "a base folder"});
  recon::BaseSetOptions options;
  options.markers.spacing = args.spacing;
  options.capture = {args.noiseCm / 100, args.dropout, args.seed};
  options.reconstruction = datasetReconstructionOptions(args);
  options.lengthModel = lengthModelSource(args.lengthModel);
  options.threads = args.threads;
  const recon::BaseSetReport report = recon::writeDatasetBases(datasetFolder(args.dataset), args.writeBase, options);
  std::cout << "reconstruct: base folder " << args.writeBase << " of " << args.dataset << ": " << report.summary()
            << "\n";
}

void runReconstruct(const ReconstructArgs& args) {
  if (args.quiet) core::setLogLevel(core::LogLevel::Warning);
  if (!args.markersSequence.empty()) {
    PIXELCLOTH_CHECK(args.dataset.empty() && args.writeBase.empty(),
                     "reconstruct --markers-sequence: not with --dataset or --write-base");
    return runFromMarkerSequence(args);
  }
  PIXELCLOTH_CHECK(args.model.empty() && args.motion.empty(),
                   "reconstruct: --model and --motion go with --markers-sequence");
  PIXELCLOTH_CHECK(args.markers.empty() != args.dataset.empty(),
                   "reconstruct: give either --markers (with --pose) or --dataset, not both or neither");
  PIXELCLOTH_CHECK(args.writeBase.empty() || !args.dataset.empty(),
                   "reconstruct --write-base needs --dataset: the bases are made from a dataset's rows");
  if (!args.markers.empty())
    runFromMarkers(args);
  else if (!args.writeBase.empty())
    runWriteBase(args);
  else
    runFromDataset(args);
}
}  // namespace

void registerReconstruct(CLI::App& app) {
  auto margs = std::make_shared<MarkersArgs>();
  CLI::App* markers = app.add_subcommand(
      "markers",
      "Define markers on a garment's cage (every junction, points along each curve); with --dataset, take their "
      "positions from a sample (optionally noisy, with dropout); with --pc2, from every frame of a garment sequence, "
      "as "
      "trajectories (docs/markers.md, docs/motion.md)");
  markers->add_option("--garment", margs->garment, std::string(kGarmentHelp) + " (ignored with --dataset, which "
                                                   "carries its garment)")->capture_default_str();
  markers->add_option("--spacing", margs->spacing, "Marker spacing along the curves, metres")->capture_default_str();
  markers->add_option("--dataset", margs->dataset, "Dataset folder to take positions from");
  markers->add_option("--sample", margs->sample, "Sample index in the dataset")->capture_default_str();
  markers->add_option("--noise", margs->noiseCm, "Gaussian noise per coordinate, cm")->capture_default_str();
  markers->add_option("--dropout", margs->dropout, "Fraction of curve markers left out (junctions kept)")
      ->capture_default_str();
  markers->add_option("--seed", margs->seed, "Seed of noise and dropout")->capture_default_str();
  markers->add_option("--pose-out", margs->poseOut, "Also write the sample's pose (JSON, for reconstruct --pose)");
  markers->add_option("--pc2", margs->pc2,
                      "A garment sequence's point cache (garment.pc2, as predict --motion writes it): the markers' "
                      "positions in every frame, written with --trajectories");
  markers->add_option("--trajectories", margs->trajectories,
                      "With --pc2: the marker trajectories (NPY, frames x markers x 3, NaN where dropped), for "
                      "reconstruct --markers-sequence");
  markers->add_option("--out", margs->out, "Marker file (JSON)")->required();
  markers->callback([margs] { runMarkers(*margs); });

  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* verb = app.add_subcommand(
      "reconstruct",
      "Rebuild garments from sparse markers: length-preserving spline cage, procedural patch fill. Either "
      "--markers M.json --pose P.json --out garment.obj, or --dataset DIR --split S --out DIR (every method, "
      "metrics.json, error maps), or --dataset DIR --write-base DIR (base offsets and marker features of every row, "
      "for the learned refinement; docs/reconstruction.md), or --markers-sequence T.npy --markers M.json --motion M "
      "--out DIR (every frame of a capture, as predict --motion writes them; docs/motion.md)");
  verb->add_option("--markers", args->markers, "Marker file with positions (pixelcloth markers; docs/markers.md)");
  verb->add_option("--pose", args->pose, "Pose of the body (JSON, as pixelcloth pose reads it)");
  verb->add_option("--body", args->body, "Body folder (default: the built-in mannequin, dressed on the fly)");
  verb->add_option("--garment", args->garment,
                   std::string(kGarmentHelp) + " (markers form; default: the --dressing folder's garment, else the "
                   "template the marker file names)");
  verb->add_option("--dressing", args->dressing,
                   "Folder with body/, rest_positions.npy and embedding_*.npy (e.g. a dataset) instead of dressing");
  verb->add_option("--method", args->method, "linear, catmull_rom, spline or spline_anisotropic")
      ->capture_default_str();
  verb->add_option("--dataset", args->dataset, "Dataset folder: reconstruct every sample of --split by every method");
  verb->add_option("--split", args->split, "train, regularisation, test or all")
      ->capture_default_str()
      ->check(CLI::IsMember({"train", "regularisation", "test", "all"}));
  verb->add_option("--noise", args->noiseCm, "Marker noise, cm (dataset form)")->capture_default_str();
  verb->add_option("--dropout", args->dropout, "Fraction of curve markers dropped (dataset form)")
      ->capture_default_str();
  verb->add_option("--spacing", args->spacing, "Marker spacing along the curves, metres (dataset form)")
      ->capture_default_str();
  verb->add_option("--seed", args->seed, "Seed of noise and dropout (dataset form)")->capture_default_str();
  verb->add_option("--meshes", args->meshes, "Samples written as OBJ (dataset form)")->capture_default_str();
  verb->add_option("--rest-lengths", args->restLengths, "Curve rest lengths: pattern, polyline or geodesic")
      ->capture_default_str();
  verb->add_option("--length-tolerance", args->spline.lengthTolerance,
                   "Spline: relative segment-length error that costs as much as a unit residual")
      ->capture_default_str();
  verb->add_option("--stretch", args->spline.stretch,
                   "Spline: segments may be longer than their rest length (cloth stretches); false: exact lengths")
      ->capture_default_str();
  verb->add_option("--tangent-prior", args->spline.tangentPrior, "Spline: weight of the Catmull-Rom tangent prior")
      ->capture_default_str();
  verb->add_option("--bending", args->spline.bendingWeight, "Spline: weight of the bending term")
      ->capture_default_str();
  verb->add_option("--length-model", args->lengthModel,
                   "Spline: worn segment lengths. Dataset form: fit (on the train split; default), none (rest "
                   "lengths) or a length_model.json; markers form: a length_model.json, or none (default)");
  verb->add_option("--aniso-theta", args->anisoThetaDegrees,
                   "spline_anisotropic: pattern-space direction of faster diffusion, degrees (0 = u, 90 = v)")
      ->capture_default_str();
  verb->add_option("--aniso-ratio", args->anisoRatio, "spline_anisotropic: diffusion across / along, in (0, 1]")
      ->capture_default_str();
  verb->add_option("--body-clearance", args->bodyClearance,
                   "Rebuilt vertices nearer the body than this (metres) are moved out to it; negative: never")
      ->capture_default_str();
  verb->add_option("--out", args->out, "garment.obj (markers form) or output folder (dataset form)");
  verb->add_option("--write-base", args->writeBase,
                   "Dataset form: instead of --out, write a base folder (base offsets and marker features of every "
                   "row, spline_anisotropic; docs/dataset.md)");
  verb->add_option("--threads", args->threads,
                   "--write-base, --markers-sequence: samples or frames rebuilt at once (0: one per core)")
      ->capture_default_str();
  verb->add_option("--markers-sequence", args->markersSequence,
                   "Marker trajectories (NPY frames x markers x 3, or CSV of one frame a line; NaN or empty where a "
                   "marker is not seen) of the markers in --markers, in the motion's world: with --motion, every "
                   "frame rebuilt and written as a sequence (animation.glb, OBJ frames, PC2 caches, metrics.json; "
                   "docs/motion.md)");
  verb->add_option("--motion", args->motion, "--markers-sequence: the body's motion (pixelcloth motion import)");
  verb->add_option(
      "--model", args->model,
      "--markers-sequence: a residual model (train --residual) that refines every frame; its dataset holds "
      "the body and garment");
  addEngineOption(*verb, args->engine);
  addStitchOptions(*verb, args->stitch, false);
  verb->add_flag("--quiet", args->quiet, "No progress on stderr");
  verb->callback([args, verb] {
    for (const char* name : {"--split", "--meshes", "--method"})
      if (verb->count(name) > 0) args->evaluationOptions.push_back(name);
    for (const char* name : {"--pose", "--body", "--dressing"})
      if (verb->count(name) > 0) args->markersOptions.push_back(name);
    runReconstruct(*args);
  });
}

}  // namespace pixelcloth::apps
