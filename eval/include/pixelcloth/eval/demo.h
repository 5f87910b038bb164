#pragma once

// The demo's computations (DESIGN.md, "eval/"): the simulated datasets, the pose filter, the marker reconstruction,
// the learned models, the stitching and the paper's tables on the demo's shirts, and a garment brought as another
// program's OBJ, each run through the library in a folder of the demo's report and returned typed. viz/ draws them
// (viz/demo.h); `pixelcloth demo` sequences both.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/eval/experiments.h"
#include "pixelcloth/eval/motion_prediction.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/garment/obj_import.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/learn/training_data.h"
#include "pixelcloth/patches/body_fit.h"
#include "pixelcloth/recon/base.h"
#include "pixelcloth/recon/reconstruct.h"
#include "pixelcloth/sim/shape_comparison.h"
#include "pixelcloth/stitch/evaluate.h"
#include "pixelcloth/stitch/gan.h"

namespace pixelcloth::eval {

/// How much the demo does.
struct DemoPlan {
  int poses = 12;              ///< random poses shown
  int filterPoses = 200;       ///< poses drawn, pruned and simulated for the filtering histograms
  int tshirtSamples = 40;      ///< the simulated T-shirt dataset; its test split is rebuilt from markers
  int necktieSamples = 6;      ///< the simulated necktie dataset
  int learningEpochs = 8;      ///< epochs of each learned model on the T-shirt dataset
  int necktieEpochs = 60;      ///< epochs of the necktie decoder
  int ownGarmentSamples = 20;  ///< the simulated dataset of the imported garment
  int equilibriumSamples = 8;  ///< the T-shirt dataset's first poses run to static equilibrium (Newton)
  std::uint64_t seed = 1;
};

/// A garment dressed on the body.
struct DressedGarment {
  garment::Garment garment;
  cage::Dressing dressing;
};
/// The T-shirt and the necktie dressed on `body` (cage::dressGarment on the body's and the garment's cages).
std::vector<DressedGarment> dressTemplates(const body::Body& body);

/// A simulated dataset, checked.
struct SimulatedDataset {
  std::filesystem::path folder;
  double seconds = 0;  ///< simulation wall time
  data::DatasetCheckReport check;
  data::DatasetInfo info;
};

/// `count` samples of `garment` (a template name or a garment folder) simulated on the body of `bodyFolder` into
/// `folder` (emptied first), then checked.
SimulatedDataset simulateDataset(const std::filesystem::path& folder, const std::filesystem::path& bodyFolder,
                                 const std::string& garment, int count, std::uint64_t seed,
                                 sim::SolverKind solver = sim::SolverKind::ProjectiveDynamics);

/// The T-shirt dataset's first poses run to static equilibrium by the Newton solver (`generate --solver newton`, the
/// same seed) into `folder`, and projective dynamics' samples of the same poses (the dataset at `projective`)
/// compared with them through the pattern, pose by pose.
struct EquilibriumDemo {
  SimulatedDataset newton;
  sim::ShapeComparison comparison;  ///< a: projective dynamics' samples, b: the equilibria
  std::filesystem::path projective;
};
EquilibriumDemo runEquilibriumDemo(const std::filesystem::path& folder, const std::filesystem::path& bodyFolder,
                                   const std::filesystem::path& projective, const DemoPlan& plan);

/// The appendix sampler's draws, pruned (arms in the torso) and simulated on the T-shirt: the poses at each stage and
/// the tally of a dataset manifest.
struct PoseFiltering {
  std::vector<body::Pose> drawn, simulated, kept;
  data::DatasetStats tally;
  double seconds = 0;  ///< summed simulation time (one core each)
};
PoseFiltering filterSampledPoses(const body::Body& body, int count, std::uint64_t seed);

/// The T-shirt dataset rebuilt from markers by every method into `out`: its test split, or every sample when it has
/// none. `shown`: the first two rebuilt rows, whose meshes are in out/sample_NNNNNN/.
struct DemoReconstruction {
  recon::DatasetReconstructionReport report;
  std::vector<int> shown;
};
DemoReconstruction reconstructDemoDataset(const std::filesystem::path& dataset, const std::filesystem::path& out);

/// The necktie decoder (width 0.25) trained on the necktie dataset into `out` (emptied first).
learn::TrainReport trainNecktie(const std::filesystem::path& dataset, const std::filesystem::path& out,
                                const DemoPlan& plan);

/// One of the demo's learned models, trained and measured on the test split (train split when there is none).
struct DemoModel {
  std::string name, label;  ///< e.g. "patch", "28 patches, pose in"
  std::filesystem::path folder;
  learn::TrainOptions options;
  learn::TrainReport trained;
  data::Split split = data::Split::Test;
  stitch::Evaluation evaluation;
  stitch::RowPredictions shown;  ///< the predictions of DemoLearning::shown
};

/// The demo's learned models on the T-shirt dataset: the marker reconstruction of every sample as the residual models'
/// base (bases_tshirt/), a whole-garment decoder, the 28 patch decoders and the residual patch decoders
/// (model_whole/, model_patch/, model_residual_patch/).
struct DemoLearning {
  recon::BaseSetReport bases;
  learn::TrainingData data;  ///< the dataset as the pose-only models read it (truth, poses)
  std::vector<int> shown;    ///< the split's first two rows
  std::vector<DemoModel> models;
  double markersAloneCm = 0;  ///< the base's error on the split
};
DemoLearning runDemoLearning(const std::filesystem::path& report, const DemoPlan& plan);

/// The paper's Tables 1 and 2 and its whole-against-patches comparison on the demo's shirts (paper_tables/), and the
/// patch decoders of runDemoLearning stitched every way: the mean, feathered weights, the PCA filter at the k chosen
/// on the regularisation split, a GAN blender trained here (model_gan/); measured on the test split.
struct DemoSeams {
  int trainSamples = 0, epochs = 0, pcaComponents = 0;
  std::vector<ModelFigures> table1, wholeVsPatches, table2;
  stitch::GanOptions ganOptions;
  stitch::GanReport gan;
  std::int64_t ganParameters = 0;
  stitch::StitchMode chosen;  ///< the PCA filter's k chosen on the regularisation split
  data::Split split = data::Split::Test;
  learn::TrainingData data;
  std::vector<stitch::Evaluation> measured;  ///< mean, feather, the chosen k, the GAN, then the rest of the sweep
  int exampleRow = 0;                        ///< the split's first row
  /// That row stitched by the mean, the chosen k and the GAN, in that order.
  std::vector<std::pair<stitch::StitchMode, Eigen::MatrixX3d>> examples;
};
DemoSeams runDemoSeams(const std::filesystem::path& report, const DemoPlan& plan);

/// A motion of the demo's own through the patch decoders of runDemoLearning: key poses from the paper's sampler eased
/// into one another with a slow turn of the root, written as an animated GLB the way other tools write clips
/// (motion/clip.glb), imported back through assimp and retargeted (motion/imported/), and predicted frame by frame
/// (motion/predicted/: eval::predictMotion's files). Then the predicted garment as a capture system would see it: the
/// residual models' markers in every frame, a tenth of the curve markers lost in each (motion/markers/), rebuilt frame
/// by frame and refined by the residual patch decoders (motion/reconstructed/).
struct DemoMotion {
  std::filesystem::path clip, imported, predicted, markers, reconstructed;
  int keyPoses = 0;
  motion::Motion motion;          ///< as imported
  double maxRetargetDegrees = 0;  ///< the imported poses against the ones written, the largest joint angle apart
  MotionPrediction prediction;
  double markerDropout = 0.1;
  int markerCount = 0;
  MotionPrediction reconstruction;
  /// Mean vertex distance from the predicted garment the markers were taken from, over the frames, cm: of the base
  /// the markers alone rebuild, and of the refined garment.
  double baseErrorCm = 0, reconstructionErrorCm = 0;
};
DemoMotion runDemoMotion(const std::filesystem::path& report, const DemoPlan& plan);

/// Writes the T-shirt OBJ a user brings, as other cloth programs write theirs: 2000 vertices, each sleeve one
/// tube-shaped UV island cut along the underarm (several UVs per vertex there), Z up, centimetres, its origin 90 cm
/// below and 5 cm behind the body's, vertices shuffled. Returns the import options that read it back into place
/// (garment::importGarmentObj), named "my_shirt".
garment::ObjImportOptions writeOwnShirtObj(const std::filesystem::path& obj);

/// A T-shirt OBJ written the way other cloth programs write theirs (tube sleeves with several UVs per vertex, Z up,
/// centimetres, another origin), imported without a cage file and taken through the pipeline as a garment folder in
/// `folder`: fitted to the body, dressed, simulated, rebuilt from markers, per-patch decoders trained and evaluated.
struct OwnGarment {
  std::filesystem::path folder, garmentFolder;
  int fileVertices = 0, fileUvs = 0, fileFaces = 0;
  garment::Garment garment;  ///< imported and fitted
  garment::ObjImportReport import;
  int piecePatches = 0;  ///< patches before the fit
  patches::BodyFitReport fit;
  cage::Dressing dressing;
  SimulatedDataset dataset;
  recon::DatasetReconstructionReport reconstruction;
  DemoModel model;
  learn::TrainingData data;
  std::vector<int> shown;
};
OwnGarment runOwnGarment(const std::filesystem::path& folder, const body::Body& body,
                         const std::filesystem::path& bodyFolder, const DemoPlan& plan);

}  // namespace pixelcloth::eval
