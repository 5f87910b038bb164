// pixelcloth dataset info|check|stats|merge|import|rebase: look at, verify, picture, merge, import and rebase dataset
// folders
// (docs/dataset.md).
#include "pixelcloth/data/dataset.h"

#include <iostream>
#include <memory>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/data/face_statistics.h"
#include "pixelcloth/sim/generate.h"
#include "pixelcloth/sim/shape_comparison.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/pose_figures.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {

struct DatasetArgs {
  std::string folder;
  std::string other;
  int imageSize = 512;
  bool json = false;
  int strongSamples = 3;
  std::string out;
  std::vector<std::string> shards;
  std::string objs;
  std::string poses;
  std::string garment = "tshirt";
  std::string body;
  std::string dressing;
  std::uint64_t seed = 0;
};

void runInfo(const DatasetArgs& args) {
  const data::DatasetInfo info = data::readDatasetInfo(datasetFolder(args.folder));
  if (args.json) {
    nlohmann::json summary = info.manifest;
    summary.erase("checksums");
    summary["folder"] = info.folder.string();
    std::cout << summary.dump(2) << '\n';
  } else {
    std::cout << info.summary();
  }
}

void runCheck(const DatasetArgs& args) {
  data::DatasetCheckOptions options;
  options.strongSamples = args.strongSamples;
  const data::DatasetCheckReport report = data::checkDataset(args.folder, options);
  std::cout << "ok: " << args.folder << ": " << report.summary() << '\n';
}

/// The paper's appendix statistics as pictures: per face, the smallest and largest area ratio over the samples, and
/// how often it intersects the garment itself.
void runStats(const DatasetArgs& args) {
  core::checkOutputFolder(args.out);
  core::checkRunFolder(args.out, {"", {}, "a dataset's face statistics"});
  const data::Dataset dataset = data::openDataset(datasetFolder(args.folder));
  const data::FaceStatistics stats = data::faceStatistics(dataset);
  const garment::Garment garment = data::datasetGarment(dataset.info);
  viz::writeFaceStatistics(garment, stats, dataset.info.folder, args.out);
  std::cout << "face statistics of " << stats.samples << " samples: area ratio " << stats.minAreaRatio.minCoeff()
            << " to " << stats.maxAreaRatio.maxCoeff() << ", " << stats.samplesSelfIntersecting
            << " samples with the garment passing through itself -> " << args.out
            << "/{area_distortion.png, self_intersection.png, face_statistics.json}\n";
  if (dataset.info.settings.source != "simulated") return;
  // The joint angles before and after filtering: the sampler's draws for these samples made again from the seed.
  const sim::SampledPoses poses =
      sim::datasetPoseDraws(dataset, data::loadDatasetBody(dataset.info.folder), garment.traits);
  core::writePng(
      std::filesystem::path(args.out) / "joint_angles.png",
      viz::renderJointHistograms({{"drawn", poses.drawn, {175, 175, 175}},
                                  {"simulated (after pruning arms in the torso)", poses.simulated, {140, 185, 235}},
                                  {"kept (the simulation's acceptance test)", poses.kept, {30, 80, 190}}}));
  auto bin = [](const viz::JointBinLoss& loss) {
    return nlohmann::json{{"joint", loss.joint},
                          {"axis", loss.axis},
                          {"lower_degrees", loss.lowerDegrees},
                          {"upper_degrees", loss.upperDegrees},
                          {"before", loss.before},
                          {"after", loss.after},
                          {"kept_fraction", loss.keptFraction()}};
  };
  core::writeJson(std::filesystem::path(args.out) / "pose_filtering.json",
                  nlohmann::json{{"drawn", poses.drawn.size()},
                                 {"simulated", poses.simulated.size()},
                                 {"kept", poses.kept.size()},
                                 {"worst_bin_simulation", bin(viz::worstJointBin(poses.simulated, poses.kept))},
                                 {"worst_bin_overall", bin(viz::worstJointBin(poses.drawn, poses.kept))}});
  std::cout << "joint angles: " << poses.drawn.size() << " poses drawn, " << poses.simulated.size() << " simulated, "
            << poses.kept.size() << " kept -> " << args.out << "/{joint_angles.png, pose_filtering.json}\n";
}

void runCompare(const DatasetArgs& args) {
  const data::Dataset a = data::openDataset(datasetFolder(args.folder));
  const data::Dataset b = data::openDataset(datasetFolder(args.other));
  const sim::ShapeComparison c = sim::compareDatasets(a, b, args.imageSize);
  if (args.json) {
    nlohmann::ordered_json out{{"a", args.folder},
                               {"b", args.other},
                               {"rows_a", c.rowsA},
                               {"rows_b", c.rowsB},
                               {"posed_alike", c.rows.size()},
                               {"mean_distance_cm", 100 * c.meanDistance()},
                               {"max_distance_cm", 100 * c.maxDistance()},
                               {"samples", nlohmann::json::array()}};
    for (size_t k = 0; k < c.rows.size(); ++k)
      out["samples"].push_back({{"row_a", c.rows[k].first},
                                {"row_b", c.rows[k].second},
                                {"mean_distance_cm", 100 * c.mean[k]},
                                {"max_distance_cm", 100 * c.max[k]}});
    std::cout << out.dump(2) << '\n';
    return;
  }
  PIXELCLOTH_CHECK(!c.rows.empty(), "dataset compare: no sample of " << args.other << " (" << c.rowsB
                                                                     << ") has the pose of one of " << args.folder
                                                                     << " (" << c.rowsA << "): nothing to compare");
  std::cout << c.rows.size() << " samples posed alike (of " << c.rowsA << " and " << c.rowsB << "): mean distance "
            << 100 * c.meanDistance() << " cm (over the samples, of the mean over the second garment's vertices), "
            << "largest " << 100 * c.maxDistance() << " cm\n";
}

void runMerge(const DatasetArgs& args) {
  std::vector<std::filesystem::path> shards(args.shards.begin(), args.shards.end());
  const data::DatasetInfo info = data::mergeDatasets(shards, args.out);
  std::cout << "merged " << shards.size() << " shards: " << info.settings.rows() << " samples -> " << args.out << '\n';
}

void runImport(const DatasetArgs& args) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  const std::filesystem::path objsPath(args.objs);
  std::error_code ec;
  const std::vector<std::filesystem::path> objs = std::filesystem::is_directory(objsPath, ec)
                                                      ? data::objSequence(objsPath)
                                                      : std::vector<std::filesystem::path>{objsPath};
  checkOutputFolder(args.out);
  const Garment garment = resolveGarment(args.garment, "--garment");
  // Fail on a bad pose file before the body and the dressing are built.
  data::readPoseSequence(args.poses, garment.traits.poseSize());
  PIXELCLOTH_CHECK(args.body.empty() || args.dressing.empty(),
                   "dataset import: --body and --dressing exclude each other: the dressing "
                   "folder holds the body its embedding was made on");
  Body body;
  Eigen::MatrixX3d rest;
  Embedding embedding;
  nlohmann::json bodyDescription;
  if (!args.dressing.empty()) {
    const std::filesystem::path dressingFolder(args.dressing);
    data::DressingFiles dressed = data::loadDressingFiles(datasetFolder(dressingFolder), garment);
    body = std::move(dressed.body);
    rest = std::move(dressed.rest);
    embedding = std::move(dressed.embedding);
    bodyDescription = {{"kind", "folder"}, {"path", (dressingFolder / "body").string()}};
  } else {
    // Dress the garment here, on the given body folder or the built-in mannequin.
    body = args.body.empty() ? makeMannequin() : loadBody(args.body);
    bodyDescription = args.body.empty() ? nlohmann::json{{"kind", "mannequin"}, {"shape", 0.0}}
                                        : nlohmann::json{{"kind", "folder"}, {"path", args.body}};
    const cage::Dressing dressing = cage::dressGarment(body, cage::bodyCage(body), garment, cage::garmentCage(garment));
    rest = dressing.relaxed;
    embedding = dressing.embedding;
  }
  data::ImportOptions options;
  options.body = bodyDescription;
  options.seed = args.seed;
  options.beyondLimits = poseLimits();
  const data::DatasetSettings settings =
      data::importDataset(objs, args.poses, body, garment, rest, embedding, args.out, options);
  std::cout << "imported " << settings.count << " frames -> " << args.out << '\n';
}

void runRebase(const DatasetArgs& args) {
  core::checkOutputFolder(args.out);
  const std::filesystem::path bodyFolder(args.body);
  std::error_code ec;
  PIXELCLOTH_CHECK(!std::filesystem::exists(bodyFolder / "manifest.json", ec),
                   "dataset rebase: --body " << args.body << " is a dataset folder; give a body folder (pixelcloth "
                                             << "body --out), e.g. " << (bodyFolder / "body").string());
  const body::Body body = body::loadBody(bodyFolder);
  const nlohmann::json description = {{"kind", "folder"},
                                      {"path", std::filesystem::absolute(bodyFolder).lexically_normal().string()}};
  const data::DatasetSettings settings = data::rebaseDataset(datasetFolder(args.folder), body, description, args.out);
  std::cout << "rebased " << settings.rows() << " samples onto " << args.body << " -> " << args.out << '\n';
}

}  // namespace

void registerDataset(CLI::App& app) {
  auto args = std::make_shared<DatasetArgs>();
  CLI::App* verb = app.add_subcommand(
      "dataset",
      "Dataset folders (manifest.json + poses/positions/offsets/split .npy): info, check, stats, compare, merge, "
      "import, rebase");
  verb->require_subcommand(1);

  CLI::App* info = verb->add_subcommand("info",
                                        "Print a readable summary of a dataset: garment, body, samples, "
                                        "splits, solver statistics, rejections");
  info->add_option("folder", args->folder, "Dataset folder")->required();
  info->add_flag("--json", args->json, "Print the manifest (without checksums) as JSON instead");
  info->callback([args] { runInfo(*args); });

  CLI::App* check = verb->add_subcommand(
      "check",
      "Verify a dataset: manifest, checksums (CRC-32), shapes, finite values, splits, and offsets recomputed "
      "from positions for a few samples. Prints 'ok' or fails with exit code 2 and the reason");
  check->add_option("folder", args->folder, "Dataset folder")->required();
  check->add_option("--strong", args->strongSamples, "Samples whose offsets are recomputed from positions")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  check->callback([args] { runCheck(*args); });

  CLI::App* stats = verb->add_subcommand(
      "stats",
      "The paper's appendix statistics as pictures: per garment face, the smallest and largest ratio of its area to "
      "its pattern area over the samples (area_distortion.png) and the fraction of samples in which it passes "
      "through the garment itself (self_intersection.png), with the numbers in face_statistics.json; for a simulated "
      "dataset also the joint-angle histograms of the sampler's draws, of the poses simulated and of those kept "
      "(joint_angles.png, pose_filtering.json)");
  stats->add_option("folder", args->folder, "Dataset folder")->required();
  stats->add_option("--out", args->out, "Output folder for the pictures")->required();
  stats->callback([args] { runStats(*args); });

  CLI::App* compare = verb->add_subcommand(
      "compare",
      "How far apart two datasets' samples of the same poses are: per pose both hold (identical pose vectors), the "
      "distance between the two shapes at each point of the sewing pattern (vertex to vertex on one mesh; through "
      "cloth images on two meshes of a pattern), mean and largest, in cm: meshes of different resolution, or two "
      "continuation paths (generate --step-degrees)");
  compare->add_option("folder", args->folder, "First dataset folder")->required();
  compare->add_option("other", args->other, "Second dataset folder")->required();
  compare->add_option("--image-size", args->imageSize, "Cloth image size for meshes of different resolution")
      ->capture_default_str()
      ->check(CLI::Range(64, 4096));
  compare->add_flag("--json", args->json, "Print every pair as JSON");
  compare->callback([args] { runCompare(*args); });

  CLI::App* merge = verb->add_subcommand(
      "merge", "Merge the shard folders of one dataset (pixelcloth generate --shard K/N) into one, in index order");
  merge->add_option("--out", args->out, "Output folder (new or empty)")->required();
  merge->add_option("shards", args->shards, "Shard folders, all of them, in any order")->required();
  merge->callback([args] { runMerge(*args); });

  CLI::App* import = verb->add_subcommand(
      "import",
      "Import garment shapes from another simulator or capture: an OBJ sequence (same vertices and faces "
      "as the garment) with one pose per frame");
  import->add_option("--objs", args->objs, "Folder of OBJ files (natural name order), or one OBJ file")->required();
  import
      ->add_option("--poses", args->poses,
                   "Poses, one per OBJ: JSON (list of pose objects or of 90-number arrays) or CSV (one row of 90, "
                   "or 9 per joint that drives the garment, 36 for the necktie, numbers per frame; optional header)")
      ->required();
  import->add_option("--garment", args->garment, kGarmentHelp)->capture_default_str();
  import->add_option("--body", args->body,
                     "Body folder (pixelcloth body --out) to dress the garment on (default: the built-in mannequin)");
  import->add_option("--dressing", args->dressing,
                     "Folder with body/, rest_positions.npy and embedding_*.npy (e.g. a generated dataset): import "
                     "with that body and dressing");
  import->add_option("--seed", args->seed, "Seed of the train / regularisation / test split")->capture_default_str();
  import->add_option("--out", args->out, "Output dataset folder")->required();
  import->callback([args] { runImport(*args); });

  CLI::App* rebase = verb->add_subcommand(
      "rebase",
      "The same samples on another body (another shape, or corrupted skin weights): positions and poses kept, the "
      "rest garment embedded afresh on the body and every sample's offsets recomputed on it");
  rebase->add_option("folder", args->folder, "Dataset folder")->required();
  rebase->add_option("--body", args->body, "Body folder (pixelcloth body --out) with the dataset body's skeleton")
      ->required();
  rebase->add_option("--out", args->out, "Output dataset folder")->required();
  rebase->callback([args] { runRebase(*args); });

  for (CLI::App* sub : verb->get_subcommands({})) sub->fallthrough();
}

}  // namespace pixelcloth::apps
