// pixelcloth markers / reconstruct: marker sets on the cage, and garments rebuilt from them (issue 5).
#include "pixelcloth/recon/reconstruct.h"

#include <cmath>
#include <iostream>
#include <memory>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/viz/pictures.h"
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
};

garment::Garment garmentByName(const std::string& name, const std::string& context) {
  PIXELCLOTH_CHECK(name == "tshirt" || name == "necktie",
                   context << ": unknown garment '" << name << "', expected tshirt or necktie");
  return garment::makeGarment(name, "--garment");
}

void runMarkers(const MarkersArgs& args) {
  cage::MarkerOptions options;
  options.spacing = args.spacing;
  options.validate();
  cage::CaptureOptions capture{args.noiseCm / 100, args.dropout, args.seed};
  capture.validate();
  if (args.dataset.empty()) {
    const garment::Garment garment = garmentByName(args.garment, "markers --garment");
    cage::writeMarkers(args.out, cage::defineMarkers(garment, cage::garmentCage(garment), options));
    PIXELCLOTH_INFO("markers: " << garment.name << " marker definition -> " << args.out);
    return;
  }
  const data::Dataset dataset = data::openDataset(args.dataset);
  const int row = args.sample - dataset.info.settings.first();
  PIXELCLOTH_CHECK(row >= 0 && row < dataset.rows(),
                   "markers --sample " << args.sample << ": " << args.dataset << " holds samples "
                                       << dataset.info.settings.first() << " to " << dataset.info.settings.end() - 1);
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
  std::string markers, pose, body, dressing, dataset, split = "test", out, method = "spline";
  double noiseCm = 0, dropout = 0, spacing = 0.10;
  std::uint64_t seed = 0;
  int meshes = 3;
  std::string restLengths = "pattern";
  std::string lengthModel;  // markers form: none by default; dataset form: "fit" by default
  double anisoThetaDegrees = 0, anisoRatio = 0.6;
  double bodyClearance = 0.001;
  cage::SplineOptions spline;
  bool quiet = false;
};

void runFromMarkers(const ReconstructArgs& args) {
  PIXELCLOTH_CHECK(!args.pose.empty(), "reconstruct --markers needs --pose (the body's pose, JSON)");
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
  const body::Pose pose = body::readPose(args.pose);
  const garment::Garment garment = garmentByName(markers.garment, args.markers);
  const cage::Cage cage = cage::garmentCage(garment);
  markers.validate(garment, cage, args.markers, true);
  body::Body body;
  Eigen::MatrixX3d rest;
  garment::Embedding embedding;
  if (!args.dressing.empty()) {
    body = data::loadDatasetBody(args.dressing);
    rest = data::loadDatasetRestPositions(args.dressing, garment.mesh.numVertices());
    embedding = data::loadDatasetEmbedding(args.dressing, body.mesh.numFaces());
    PIXELCLOTH_CHECK(embedding.size() == garment.mesh.numVertices(),
                     args.dressing << "/embedding_triangle.npy: " << embedding.size() << " cloth pixels, the "
                                   << garment.name << " has " << garment.mesh.numVertices());
  } else {
    body = args.body.empty() ? body::makeMannequin() : body::loadBody(args.body);
    const cage::Dressing dressing = cage::dressGarment(body, cage::bodyCage(body), garment, cage);
    rest = dressing.relaxed;
    embedding = dressing.embedding;
  }
  if (options.lengthModel) options.lengthModel->validate(garment.name, cage, args.lengthModel);
  const recon::GarmentReconstructor reconstructor(body, garment, embedding, rest, options);
  const recon::Reconstruction result = reconstructor.reconstruct(markers, pose, method);
  core::Mesh mesh = garment.mesh;
  mesh.V = result.positions;
  core::writeMesh(args.out, mesh);
  PIXELCLOTH_INFO("reconstruct: " << garment.name << " from " << markers.markers.size() << " markers (" << args.method
                                  << "; " << result.spline.summary() << ") -> " << args.out);
}

void runFromDataset(const ReconstructArgs& args) {
  recon::DatasetReconstructionOptions options;
  options.split = args.split;
  options.markers.spacing = args.spacing;
  options.capture = {args.noiseCm / 100, args.dropout, args.seed};
  options.reconstruction.spline.restLengths = cage::restLengthsFromName(args.restLengths, "reconstruct --rest-lengths");
  // Noisy markers are fitted softly, with the noise as their sigma.
  options.reconstruction.spline.markerSigma = args.noiseCm / 100;
  options.reconstruction.spline.lengthTolerance = args.spline.lengthTolerance;
  options.reconstruction.spline.bendingWeight = args.spline.bendingWeight;
  options.reconstruction.spline.stretch = args.spline.stretch;
  options.reconstruction.spline.tangentPrior = args.spline.tangentPrior;
  options.lengthModel = args.lengthModel.empty() ? "fit" : args.lengthModel;
  options.reconstruction.anisotropic.theta = args.anisoThetaDegrees * M_PI / 180;
  options.reconstruction.anisotropic.ratio = args.anisoRatio;
  options.reconstruction.bodyClearance = args.bodyClearance;
  options.meshes = args.meshes;
  options.quiet = args.quiet;
  const recon::DatasetReconstructionReport report = recon::reconstructDataset(args.dataset, args.out, options);
  core::writePng(std::filesystem::path(args.out) / "error_maps.png",
                 viz::renderReconstructionErrors(data::datasetGarment(data::readDatasetInfo(args.dataset)), report));
  for (const auto& [name, m] : report.metrics["methods"].items())
    std::cout << name << ": cage " << m["cage_cm"].get<double>() << " cm, garment " << m["garment_cm"].get<double>()
              << " cm\n";
}

void runReconstruct(const ReconstructArgs& args) {
  if (args.quiet) core::setLogLevel(core::LogLevel::Warning);
  PIXELCLOTH_CHECK(args.markers.empty() != args.dataset.empty(),
                   "reconstruct: give either --markers (with --pose) or --dataset, not both or neither");
  if (!args.markers.empty())
    runFromMarkers(args);
  else
    runFromDataset(args);
}
}  // namespace

void registerReconstruct(CLI::App& app) {
  auto margs = std::make_shared<MarkersArgs>();
  CLI::App* markers = app.add_subcommand(
      "markers",
      "Define markers on a garment's cage (every junction, points along each curve); with --dataset, take their "
      "positions from a sample (optionally noisy, with dropout) (docs/markers.md)");
  markers->add_option("--garment", margs->garment, "tshirt or necktie (ignored with --dataset)")->capture_default_str();
  markers->add_option("--spacing", margs->spacing, "Marker spacing along the curves, metres")->capture_default_str();
  markers->add_option("--dataset", margs->dataset, "Dataset folder to take positions from");
  markers->add_option("--sample", margs->sample, "Sample index in the dataset")->capture_default_str();
  markers->add_option("--noise", margs->noiseCm, "Gaussian noise per coordinate, cm")->capture_default_str();
  markers->add_option("--dropout", margs->dropout, "Fraction of curve markers left out (junctions kept)")
      ->capture_default_str();
  markers->add_option("--seed", margs->seed, "Seed of noise and dropout")->capture_default_str();
  markers->add_option("--pose-out", margs->poseOut, "Also write the sample's pose (JSON, for reconstruct --pose)");
  markers->add_option("--out", margs->out, "Marker file (JSON)")->required();
  markers->callback([margs] { runMarkers(*margs); });

  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* verb = app.add_subcommand(
      "reconstruct",
      "Rebuild garments from sparse markers: length-preserving spline cage, procedural patch fill. Either "
      "--markers M.json --pose P.json --out garment.obj, or --dataset DIR --split S --out DIR (every method, "
      "metrics.json, error maps)");
  verb->add_option("--markers", args->markers, "Marker file with positions (pixelcloth markers; docs/markers.md)");
  verb->add_option("--pose", args->pose, "Pose of the body (JSON, as pixelcloth pose reads it)");
  verb->add_option("--body", args->body, "Body folder (default: the built-in mannequin, dressed on the fly)");
  verb->add_option("--dressing", args->dressing,
                   "Folder with body/, rest_positions.npy and embedding_*.npy (e.g. a dataset) instead of dressing");
  verb->add_option("--method", args->method, "linear, catmull_rom, spline or spline_anisotropic")
      ->capture_default_str();
  verb->add_option("--dataset", args->dataset, "Dataset folder: reconstruct every sample of --split by every method");
  verb->add_option("--split", args->split, "train, regularisation, test or all")->capture_default_str();
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
  verb->add_option("--out", args->out, "garment.obj (markers form) or output folder (dataset form)")->required();
  verb->add_flag("--quiet", args->quiet, "No progress on stderr");
  verb->callback([args] { runReconstruct(*args); });
}

}  // namespace pixelcloth::apps
