#pragma once

// The PCA filter (DESIGN.md, "Stitching"; the paper's section 6): stitched offsets projected on the first k principal
// components of the training split's ground truth, which smooths the kinks patch networks leave along the cage
// curves. Fitted once, saved beside the model, reloaded with the checksum of the dataset it came from.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "pixelcloth/learn/model.h"
#include "pixelcloth/learn/spaces.h"
#include "pixelcloth/learn/training_data.h"

namespace pixelcloth::stitch {

class PcaFilter {
 public:
  /// The first `rank` components (0: min(2048, train samples, 3 #V)) of the ground-truth values (`data.space`, the
  /// base added back in residual mode) of `data`'s train split, one sample a row of 3 #V. Throws InputError for an
  /// empty train split or a rank beyond min(train samples, 3 #V).
  static PcaFilter fit(const learn::TrainingData& data, int rank = 0,
                       learn::PcaMethod method = learn::PcaMethod::Randomized);

  /// Writes `folder` (created): mean.npy (3 #V), components.npy (rank x 3 #V), variance.npy (rank), all float32 in
  /// vertex-major order (v0 du dv dn, v1 ...), then pca.json (garment, vertices, space, rank, method, seconds, the
  /// dataset folder and its manifest CRC-32, the CRC-32 of each .npy), each file atomically.
  void save(const std::filesystem::path& folder) const;
  /// Reads a folder save() wrote. Throws InputError naming the file for a missing, truncated or altered file.
  static PcaFilter load(const std::filesystem::path& folder);

  /// Throws InputError unless this filter was fitted on `data`'s dataset (manifest CRC-32), garment and space.
  void checkMatches(const learn::TrainingData& data) const;
  /// Throws InputError unless this filter is for `garment`'s vertex count and `space`.
  void checkMatches(const std::string& garment, int numVertices, learn::OffsetSpace space) const;

  /// `values` (batch x 3 #V) projected on the first `k` components and back. Throws InputError for k outside
  /// [1, rank()] or values of another size.
  Eigen::MatrixXf filter(const Eigen::MatrixXf& values, int k) const;

  int rank() const { return static_cast<int>(basis_.components.rows()); }
  const learn::PcaBasis& basis() const { return basis_; }
  /// pca.json's fields.
  const nlohmann::json& info() const { return info_; }
  const std::filesystem::path& folder() const { return folder_; }

 private:
  learn::PcaBasis basis_;
  nlohmann::json info_;
  std::filesystem::path folder_;  ///< where it was loaded from or saved to; empty for a fresh fit
};

/// Where `pca:K` looks when no folder is given: the model folder's pca/ subfolder.
std::filesystem::path defaultPcaFolder(const std::filesystem::path& modelFolder);

/// The PCA filter a model's predictions on `data` are stitched with. Given a `folder`, its filter, checked against
/// `data` (its garment and space alone when `data` holds one pose and no training rows). Otherwise the model folder's
/// defaultPcaFolder when that was fitted on this dataset with `rank` components (0: any rank), else one fitted here on
/// the train split with `rank` and saved there for the next run. Throws InputError for a filter of other data, or
/// when a fit is needed and `data` has no training rows.
PcaFilter loadOrFitPcaFilter(const learn::TrainingData& data, const std::filesystem::path& modelFolder,
                             const std::filesystem::path& folder = {}, int rank = 0);

}  // namespace pixelcloth::stitch
