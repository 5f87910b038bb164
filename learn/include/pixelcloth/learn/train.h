#pragma once

// Training the paper's decoders and the baselines on a dataset (DESIGN.md, "Networks"): cloth images or per-vertex
// values made on the fly from each sample's offsets, the masked image loss with the optional normal and edge-length
// losses, Adam, model selection on the regularisation split, and checkpoints a run resumes from.

#include <cstdint>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pixelcloth/data/dataset.h"
#include "pixelcloth/learn/model.h"
#include "pixelcloth/learn/spaces.h"

namespace pixelcloth::learn {

/// The image loss on the padded UV mask: masked L1 (the paper's choice, Sec. 5.1) or L2.
enum class ImageLoss { L1, L2 };
const char* imageLossName(ImageLoss loss);  ///< "l1", "l2"
/// The loss named `name`; InputError naming `context` otherwise.
ImageLoss imageLossFromName(const std::string& name, const std::string& context);

/// How the decoders' target images are scaled while they learn. The saved weights predict metres either way: the
/// scaling is folded into the last layer when they are written.
enum class TargetScaling {
  /// Offsets in metres, as the dataset holds them.
  None,
  /// Each channel shifted and scaled to zero mean and unit spread over the train split's masked pixels. It did not
  /// help (docs/learning.md, "Why the decoders underfit"): the L1 loss then weighs the small tangential offsets as
  /// much as the normal ones, which the position error does not.
  PerChannel
};
const char* targetScalingName(TargetScaling scaling);  ///< "none", "per-channel"
/// The scaling named `name`; InputError naming `context` otherwise.
TargetScaling targetScalingFromName(const std::string& name, const std::string& context);

/// The learning rate over a run, from the rate given at the first step: constant; a cosine from it to zero over all
/// the run's steps; or a tenth of it from half the epochs and a hundredth from three quarters (step decay).
enum class Schedule { Constant, Cosine, Step };
const char* scheduleName(Schedule schedule);  ///< "constant", "cosine", "step"
/// The schedule named `name`; InputError naming `context` otherwise.
Schedule scheduleFromName(const std::string& name, const std::string& context);
/// The learning rate of step `step` (from 0) of `steps` in a run that starts at `rate`.
double scheduledRate(Schedule schedule, double rate, std::int64_t step, std::int64_t steps);

/// Settings of train().
struct TrainOptions {
  /// The architecture and width; train() fills the input size (pose, plus marker features in residual mode) and, for
  /// the baselines, the output values from the dataset.
  ModelSpec model;
  /// Patch decoders: which patches to train (ids; empty: all). Each goes to its own patch_NN/ folder of `out`, so runs
  /// with different subsets (a job array) fill one model folder.
  std::vector<int> patches;
  ImageLoss loss = ImageLoss::L1;
  /// The decoders' (whole, patch, necktie) target scaling; the baselines learn metres.
  TargetScaling targetScaling = TargetScaling::None;
  /// What the values mean; the default (unset) is the garment's (garment::GarmentTraits::rootFrameOffsets): the
  /// paper's root frame for the necktie, local frames otherwise.
  std::optional<OffsetSpace> space;
  /// Weight of the normal loss (1 - cosine of per-vertex normals); negative: the garment's (GarmentTraits; the paper's
  /// 0.01 for the T-shirt, 0.1 for the necktie).
  double normalWeight = -1;
  /// Weight of the edge-length L1 loss; negative: the garment's (the paper's 0.1 for the necktie, 0 otherwise).
  double edgeWeight = -1;
  /// Residual mode: a base folder of the dataset (`reconstruct --write-base`); the inputs gain the marker features
  /// and the targets become ground truth minus base. Empty: plain mode (pose in, values out).
  std::filesystem::path residual;
  /// Learn from only the first this many samples of the train split (its rows in dataset order, which the sampler
  /// drew at random); 0: all of them. For learning curves: the regularisation and test splits stay whole.
  int trainSamples = 0;
  int epochs = 20;          ///< passes over the train split, [1, 100000]
  int batch = 8;            ///< samples per Adam step, [1, 4096]
  double learningRate = 1e-3;
  /// The learning rate over the run. Under a decaying schedule the epochs are part of a run's settings: a finished
  /// run is not extended by more.
  Schedule schedule = Schedule::Constant;
  /// Early stopping: a network stops after this many epochs without a lower regularisation error (0: never; needs a
  /// regularisation split). Its model is the best epoch's either way.
  int patience = 0;
  std::uint64_t seed = 0;   ///< initial weights and the order of the train split in each epoch
  int threads = 0;          ///< LibTorch's intra-op threads; 0: one per core (OMP_NUM_THREADS, when set, decides)
  /// Patch decoders: how many networks train at once, each on one thread (the threads above shared out); 0: one
  /// per thread when there are two or more networks. 1: one after another, each on all the threads.
  int networksAtOnce = 0;
  void validate() const;
};

/// One epoch of one network.
struct EpochRecord {
  int epoch = 0;                     ///< from 1
  double loss = 0;                   ///< mean training loss of its steps (image term, metres for L1)
  double normalLoss = 0;             ///< mean normal term (before its weight); 0 when off
  double edgeLoss = 0;               ///< mean edge-length term, metres; 0 when off
  /// Mean per-vertex error on the train split over the epoch's steps, from their own forward passes (training mode,
  /// the weights moving), cm.
  double trainErrorCm = 0;
  /// Mean per-vertex error on the regularisation split after the epoch, on the weights it ended with (NaN when the
  /// split is empty), cm.
  double regularisationErrorCm = 0;
  double seconds = 0;
  double dataWaitSeconds = 0;        ///< of those, waiting for the prefetch thread's next batch
};

/// What training one network did.
struct NetworkReport {
  int patch = -1;  ///< the patch id of a patch decoder, -1 otherwise
  std::filesystem::path folder;
  std::vector<EpochRecord> epochs;
  int bestEpoch = 0;  ///< the epoch whose weights model.tensors holds: lowest regularisation error (else the last)
  double bestErrorCm = std::numeric_limits<double>::quiet_NaN();
  int resumedAt = 0;  ///< epochs found done in the folder's checkpoint (0: a fresh start)
  bool stoppedEarly = false;  ///< ended by TrainOptions::patience before the last epoch
};

struct TrainReport {
  std::vector<NetworkReport> networks;
  double seconds = 0;
};

/// Trains `options.model` on the train split of a finished dataset folder and writes into `out` (created, or an
/// existing folder): per network model.tensors (a tensor file of the best epoch's weights, core/tensor_file.h), model.json (architecture,
/// width, inputs, output, garment, space, loss, dataset and its manifest checksum, base folder, patch, epoch, errors),
/// log.csv (one row per epoch) and checkpoint.tensors (the last epoch's weights and optimizer state), each atomically;
/// patch decoders in patch_NN/ subfolders. Run again with the same arguments, it resumes from checkpoint.tensors (after a
/// kill -9 too) and ends with the weights of an uninterrupted run; more epochs extend a finished run. Throws
/// InputError for a model that does not fit the dataset, a base folder of another dataset, or a folder holding a run
/// with other settings.
TrainReport train(const data::DatasetFolder& dataset, const std::filesystem::path& out, const TrainOptions& options);

/// The rule for writing into a used folder (core::checkRunFolder) applied to model folders, before training: a patch
/// model (`patchModel`) keeps its decoders in patch_NN/ subfolders, every other model (and a GAN blender) its
/// model.json at the top, and each existing model.json must agree with `settings` (its fields, by value). Throws
/// InputError naming what the folder holds otherwise. `what` names the model in messages ("the fc model").
void checkModelFolder(const std::filesystem::path& out, const nlohmann::json& settings, bool patchModel,
                      const std::string& what);

}  // namespace pixelcloth::learn
