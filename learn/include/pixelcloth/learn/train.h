#pragma once

// Training a whole-garment image decoder (the whole garment or the necktie) on a dataset's cloth images, with its
// checkpoint; the patch decoders, the residual mode and the baselines' training come next (issue 12).

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "pixelcloth/learn/model.h"

namespace pixelcloth::learn {

/// Settings of trainImageModel.
struct TrainOptions {
  ModelSpec model;          ///< whole (T-shirt) or necktie; `model.inputSize` 0 (the pose)
  std::string loss = "l1";  ///< "l1" (the paper's) or "l2", masked to the padded UV mask
  int epochs = 20;          ///< passes over the train split, [1, 100000]
  int batch = 8;            ///< samples per Adam step, [1, 4096]
  double learningRate = 1e-3;
  std::uint64_t seed = 0;  ///< initial weights and the order of the train split in each epoch
  bool quiet = false;      ///< no progress on stderr
  void validate() const;
};

/// One epoch of training.
struct EpochRecord {
  int epoch = 0;                     ///< from 1
  double loss = 0;                   ///< mean training loss of its steps (metres for L1)
  double trainErrorCm = 0;           ///< mean per-vertex error on the train split after the epoch, cm
  double regularisationErrorCm = 0;  ///< the same on the regularisation split (NaN when it is empty)
  double seconds = 0;
};

/// What trainImageModel did.
struct TrainReport {
  std::vector<EpochRecord> epochs;
  int bestEpoch = 0;  ///< the epoch whose weights model.pt holds: lowest regularisation error (else the last)
  double bestErrorCm = std::numeric_limits<double>::quiet_NaN();
};

/// Trains `options.model` on the train split of a finished dataset folder: each sample's cloth image made on the fly
/// from its offsets by the raster operators (patches::ClothImager), the masked image loss, Adam. Per-vertex errors
/// come from sampling the predicted image back at the cloth pixels. Writes into `out` (created, or an existing folder):
/// model.pt (LibTorch archive of the best epoch's weights), model.json (architecture, width, input and output
/// shapes, garment, dataset folder and its manifest checksum, epoch, errors) and log.csv (one row per epoch), each
/// atomically. Throws InputError for a model that does not fit the dataset's garment or pose size.
TrainReport trainImageModel(const std::filesystem::path& dataset, const std::filesystem::path& out,
                            const TrainOptions& options);

/// A model folder written by trainImageModel: the network rebuilt from model.json, its weights from model.pt. Throws
/// InputError naming the file for a missing, truncated or foreign checkpoint.
Model loadModel(const std::filesystem::path& folder);

/// Cloth images predicted for `poses` (#poses x model inputs) as per-vertex offsets of the dataset garment's cloth
/// pixels (#poses rows, each #V x 3 in C order): the image sampled back at the cloth pixels.
Eigen::MatrixXf predictOffsets(const Model& model, const std::filesystem::path& dataset, const Eigen::MatrixXf& poses);

}  // namespace pixelcloth::learn
