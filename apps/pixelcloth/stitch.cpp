// pixelcloth stitch: a garment from 28 patch crops (EXR) that any patch networks predicted, by one stitch mode.
#include <iomanip>
#include <iostream>
#include <memory>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/learn/spaces.h"
#include "pixelcloth/patches/cloth_image.h"
#include "pixelcloth/patches/crop_files.h"
#include "pixelcloth/stitch/evaluate.h"
#include "pixelcloth/stitch/seams.h"
#include "pixelcloth/stitch/stitcher.h"
#include "pixelcloth/viz/pictures.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
namespace fs = std::filesystem;

struct StitchVerbArgs {
  std::string patches, dataset, pose, mode = "mean", pca, out;
  int sample = -1;
};

/// The patch crops of `folder` (patches::readPatchCrops) as a patch decoder's predictions (batch 1).
std::vector<learn::NetworkPrediction> readCrops(const fs::path& folder, const garment::Garment& garment) {
  std::vector<learn::NetworkPrediction> out;
  for (patches::PatchCropValues& crop : patches::readPatchCrops(folder, garment)) {
    learn::NetworkPrediction p;
    p.patch = crop.patch;
    p.vertices = std::move(crop.vertices);
    // One row, vertex by vertex: du dv dn of the first vertex, then the second's, ...
    const Eigen::MatrixXf rowMajor = crop.values.transpose();
    p.values = Eigen::Map<const Eigen::MatrixXf>(rowMajor.data(), 1, rowMajor.size());
    out.push_back(std::move(p));
  }
  return out;
}

void runStitch(const StitchVerbArgs& args) {
  PIXELCLOTH_CHECK(args.sample < 0 || args.pose.empty(), "stitch: give --sample or --pose, not both");
  core::checkOutputFolder(args.out);
  core::checkRunFolder(args.out, {"stitch.json", {}, "a stitched garment"});
  const data::DatasetInfo info = data::readDatasetInfo(datasetFolder(args.dataset));
  const garment::Garment garment = data::datasetGarment(info);
  const int V = garment.mesh.numVertices();
  const stitch::StitchMode mode = stitch::parseStitchMode(args.mode, "--mode");
  std::shared_ptr<const stitch::PcaFilter> pca;
  if (mode.kind == stitch::StitchKind::Pca) {
    PIXELCLOTH_CHECK(!args.pca.empty(), "--mode " << args.mode << ": give the filter's folder with --pca DIR "
                                                                  "(pixelcloth pca --dataset D --out DIR)");
    auto filter = std::make_shared<stitch::PcaFilter>(stitch::PcaFilter::load(args.pca));
    filter->checkMatches(garment.name, V, learn::OffsetSpace::Local);
    pca = std::move(filter);
  } else {
    PIXELCLOTH_CHECK(args.pca.empty(), "--pca goes with --mode pca:K");
  }
  const stitch::Stitcher stitcher(garment, mode, pca);
  const std::vector<learn::NetworkPrediction> crops = readCrops(args.patches, garment);

  // The pose: a dataset sample's (its ground truth then measures the result), a pose file, or the rest pose.
  body::Pose pose = body::Pose::identity();
  Eigen::MatrixX3d truth;
  if (args.sample >= 0) {
    const data::Dataset dataset = data::openDataset(datasetFolder(args.dataset));
    const int row = info.rowOfSample(args.sample, "stitch --sample");
    pose = body::Pose::fromLeading(dataset.pose(row));
    truth = dataset.positionsOf(row).cast<double>();
  } else if (!args.pose.empty()) {
    pose = body::readPose(args.pose, poseLimits());
  }
  const body::Body body = data::loadDatasetBody(datasetFolder(args.dataset));
  const garment::Embedding embedding = data::loadDatasetEmbedding(datasetFolder(args.dataset), body.mesh.F.rows());
  const garment::EmbeddedFrames frames = garment::embeddedFrames(body.posedVertices(pose), body.mesh.F, embedding);

  const Eigen::MatrixXf stitched = stitcher.refine(stitcher.assemble(crops));
  Eigen::MatrixX3f values(V, 3);
  for (int v = 0; v < V; ++v) values.row(v) = stitched.block<1, 3>(0, 3 * v);
  const Eigen::MatrixX3d positions = learn::positionsFromValues(learn::OffsetSpace::Local, frames, values);

  // Seams: the crops' gap always; with a sample's ground truth, the normal jump and the errors too.
  const std::vector<Eigen::MatrixX3d> separate =
      stitch::separatePositions(crops, learn::OffsetSpace::Local, frames, nullptr, 0);
  std::vector<stitch::PredictedPositions> parts;
  for (size_t k = 0; k < crops.size(); ++k) parts.push_back({&crops[k].vertices, separate[k]});
  const stitch::SeamLayout layout(garment);
  stitch::SeamMetrics seams(layout);
  seams.add(parts, positions, truth.rows() == V ? truth : positions);
  nlohmann::json seamJson = seams.toJson();
  if (truth.rows() != V) {  // no ground truth: only the gaps mean anything
    for (const char* key : {"normal_jump_deg", "near_seam_error_cm", "interior_error_cm"}) seamJson[key] = nullptr;
    for (nlohmann::json& c : seamJson["curves"]) c["normal_jump_deg"] = c["near_seam_error_cm"] = nullptr;
  }
  nlohmann::json report = {{"patches", args.patches},
                           {"dataset", args.dataset},
                           {"stitch", mode.name()},
                           {"pose", args.sample >= 0 ? "sample " + std::to_string(args.sample)
                                                     : args.pose.empty() ? std::string("rest") : args.pose},
                           {"seams", seamJson}};
  if (truth.rows() == V) report["vertex_error_cm"] = core::meanVertexErrorCm(positions, truth);

  core::ensureOutputFolder(args.out);
  const fs::path out(args.out);
  core::Mesh mesh = garment.mesh;
  mesh.V = positions;
  core::writeMesh(out / "garment.obj", mesh);
  const patches::ClothImage image = patches::ClothImager(garment).rasterize(values);
  patches::writeClothImage(out / "cloth.exr", image);
  core::writePng(out / "cloth.png", viz::renderClothImage(image));
  core::writeJson(out / "stitch.json", report);
  std::cout << std::fixed << std::setprecision(3) << mode.name() << ": " << crops.size() << " crops, gap "
            << (seamJson["gap_cm"]["mean"].is_number() ? seamJson["gap_cm"]["mean"].get<double>() : 0.0) << " cm (max "
            << (seamJson["gap_cm"]["max"].is_number() ? seamJson["gap_cm"]["max"].get<double>() : 0.0) << ")";
  if (truth.rows() == V)
    std::cout << ", vertex error " << report["vertex_error_cm"].get<double>() << " cm, normal jump "
              << seamJson["normal_jump_deg"].get<double>() << " deg";
  std::cout << " -> " << args.out << "/{garment.obj, cloth.exr, cloth.png, stitch.json}\n";
}
}  // namespace

void registerStitch(CLI::App& app) {
  auto args = std::make_shared<StitchVerbArgs>();
  CLI::App* verb = app.add_subcommand(
      "stitch", "A garment from patch crops predicted by any networks (patch_NN.exr, as images --crops writes them)");
  verb->add_option("--patches", args->patches, "Folder of patch_00.exr ... (160 x 160, channels du dv dn)")
      ->required();
  verb->add_option("--dataset", args->dataset, "Dataset folder: its garment and body")->required();
  verb->add_option("--sample", args->sample,
                   "Pose the garment as this dataset sample and measure it against its ground truth")
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--pose", args->pose, "Pose file (pixelcloth pose); default: the rest pose");
  verb->add_option("--mode", args->mode, "mean, feather, pca:K (with --pca) or gan:DIR")->capture_default_str();
  verb->add_option("--pca", args->pca, "PCA filter folder (pixelcloth pca) for --mode pca:K");
  verb->add_option("--out", args->out, "Output folder: garment.obj, cloth.exr, cloth.png, stitch.json")->required();
  verb->callback([args] { runStitch(*args); });
}

}  // namespace pixelcloth::apps
