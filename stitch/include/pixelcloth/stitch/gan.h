#pragma once

// The GAN blender (DESIGN.md, "Stitching"; docs/gan.md): a U-Net generator that turns a stitched whole-garment cloth
// image (256 x 256 x 6: front du dv dn, back du dv dn) into a seamless one, trained against a PatchGAN discriminator on
// (stitched prediction, ground truth) pairs of a dataset's training split, with L1 plus adversarial loss. Both are
// pix2pix's (Isola et al. 2017): the generator its unet_256, but predicting a residual added to its input (its last
// layer starts at zero, so an untrained blender is the identity); the discriminator its 70 x 70 PatchGAN, shown the
// input and a candidate output side by side (12 channels). Losses: the discriminator's binary cross-entropy with
// logits on (input, truth) as real and (input, blended) as fake, halved; the generator's the same against "real" plus
// l1Weight times the mean |blended - truth| over the channels' padded UV mask (inside and padding pixels), in metres.
// LibTorch stays inside stitch/'s .cpp files.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "pixelcloth/garment/garment.h"
#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/training_data.h"

namespace pixelcloth::stitch {

/// How the blender is built and trained.
struct GanOptions {
  /// Multiplies every channel count of both networks (pix2pix's U-Net and 70 x 70 PatchGAN at 1; 0.125 on CPU). In
  /// (0, 4].
  double width = 0.125;
  int epochs = 10;              ///< passes over the train split, [1, 100000]
  int batch = 4;                ///< samples per step, [1, 4096]
  double learningRate = 2e-4;   ///< Adam, both networks (betas 0.5, 0.999)
  /// Weight of the masked L1 term (metres) against the adversarial term, >= 0. 1000 is pix2pix's balance (100 on
  /// images in [-1, 1]) for offsets of about +-10 cm; at 100 the adversarial term wins and the error grows after the
  /// first epoch, at 10000 the discriminator wins and the blender is close to an L1 U-Net (docs/gan.md, "Measured").
  double l1Weight = 1000;
  std::uint64_t seed = 0;       ///< initial weights, dropout and the order of the train split in each epoch
  int threads = 0;              ///< LibTorch's intra-op threads; 0: one per core
  /// Throws InputError naming the field that is out of range.
  void validate() const;
};

/// One epoch of the blender.
struct GanEpoch {
  int epoch = 0;                         ///< from 1
  double generatorL1 = 0;                ///< masked L1 of the generator's output, metres (before its weight), mean
                                         ///< over the epoch's steps (training mode: dropout on)
  double generatorAdversarial = 0;       ///< the generator's BCE against "real", mean over the steps
  double discriminator = 0;              ///< the discriminator's loss (half its BCE on real plus on blended), mean
  double regularisationErrorCm = 0;      ///< mean per-vertex error of the blended garments on the regularisation
                                         ///< split (NaN when it is empty)
  double stitchedErrorCm = 0;            ///< the same for the stitched input, before blending
  double seconds = 0;
};

struct GanReport {
  std::filesystem::path folder;
  std::vector<GanEpoch> epochs;
  int bestEpoch = 0;  ///< the epoch whose generator model.tensors holds: lowest regularisation error (else the last)
  double seconds = 0;
};

/// Trains a blender for `patchModel` (a trained patch model, loaded for `data`'s garment) on `data` (loaded in the
/// patch model's space, with its base folder in residual mode): the inputs are the patch model's predictions of the
/// train split assembled by the per-vertex mean (`predictRows`), base added, rasterised to whole-garment cloth images;
/// the targets are the ground-truth values' images. Writes into `out` (created): model.tensors (the best epoch's
/// generator), model.json (architecture "gan", width, the patch model folder, the dataset and its manifest checksum,
/// space, epoch, errors), log.csv (one row per epoch), each atomically; no checkpoint (a run is minutes). Progress
/// (epoch, step, rate, ETA) on stderr, one line per epoch with its errors. The same seed and inputs give the same
/// weights (on the same number of threads). Throws InputError, before anything is written, for a model that is not a
/// patch model, one trained on another dataset (manifest CRC) or in another space, or a garment without the T-shirt's
/// two 256 x 256 layouts.
GanReport trainGan(const learn::TrainedModel& patchModel, const learn::TrainingData& data, const GanOptions& options,
                   const std::filesystem::path& out);

/// A trained blender, loaded once.
class GanBlender {
 public:
  /// Loads `folder` (trainGan's output) for `garment`. Throws InputError naming the file for a missing, truncated or
  /// foreign model.tensors or model.json, or a blender of another garment.
  GanBlender(const std::filesystem::path& folder, const garment::Garment& garment);
  ~GanBlender();
  GanBlender(GanBlender&&) noexcept;

  /// `stitched` is batch x 3 * #V per-vertex values (the model's space, base added); returns the blended values, the
  /// same shape: rasterised to cloth images, through the generator (eval mode: BatchNorm's running statistics, no
  /// dropout; no gradients), sampled back at the cloth pixels. Not for concurrent calls.
  Eigen::MatrixXf blend(const Eigen::MatrixXf& stitched) const;
  /// model.json as read.
  const nlohmann::json& info() const;
  const std::filesystem::path& folder() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Layer shapes of both networks of `width` for one 256 x 256 x 6 sample, for tests and `pixelcloth model`:
/// {"width", "generator": {"parameters", "input", "output", "layers": [{"name", "output"}]}, "discriminator": {...}}:
/// generator out 6 x 256 x 256, discriminator out 1 x 30 x 30 logits (each of a 70 x 70 window); parameters trainable.
nlohmann::json ganSummary(double width);

}  // namespace pixelcloth::stitch
