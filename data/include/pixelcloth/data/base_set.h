#pragma once

// The learned refinement's inputs (DESIGN.md, "Learned refinement"): for every sample of a dataset, the base offsets
// the marker pipeline rebuilds from that sample's own markers, and the marker features. Written by
// `pixelcloth reconstruct --dataset D --write-base OUT` (recon/), read by training and prediction (learn/).
//
// Folder layout:
//   manifest.json        {"format": "pixelcloth.base", "version": 1, "dataset": absolute path,
//                         "dataset_manifest_crc32": CRC-32 of the dataset's manifest.json, "garment", "samples": N,
//                         "first_sample", "vertices": V, "markers": M, "settings": {how the bases were made: method,
//                         marker spacing, noise, dropout, seed, body clearance, length model}, "files": {name: crc32}}
//   base_offsets.npy     float32 (N, V, 3): each dataset row's rebuilt offsets (du, dv, dn) in the embedded frames
//   marker_features.npy  float32 (N, M, 3): each marker's offset in its vertex's embedded frame (du, dv, dn), in
//                        marker definition order; a dropped marker's row is 0
// Row r of both arrays is row r of the dataset (sample first_sample + r).

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "pixelcloth/data/dataset.h"

namespace pixelcloth::data {

/// A base folder in memory.
struct BaseSet {
  std::filesystem::path folder;
  nlohmann::json manifest;
  int samples = 0, vertices = 0, markers = 0;
  Eigen::MatrixXf offsets;   ///< samples x 3 * vertices, row-major per vertex (du, dv, dn)
  Eigen::MatrixXf features;  ///< samples x 3 * markers

  Eigen::MatrixX3f offsetsOf(int row) const;  ///< vertices x 3
  Eigen::VectorXf featuresOf(int row) const;  ///< 3 * markers
};

/// Writes a base folder for the finished dataset `dataset` (every row: `offsets` rows x 3V, `features` rows x 3M)
/// atomically: arrays first, manifest.json last. `settings` goes into the manifest as is. Throws InputError for shapes
/// that do not fit the dataset or non-finite values.
void writeBaseSet(const std::filesystem::path& folder, const DatasetInfo& dataset, const Eigen::MatrixXf& offsets,
                  const Eigen::MatrixXf& features, const nlohmann::json& settings);

/// Reads a base folder and checks it against `dataset`: format, the dataset manifest's CRC-32 (a base folder of
/// another dataset, or of this one before it changed), counts, array shapes and checksums. Throws InputError naming the
/// file and what was expected.
BaseSet openBaseSet(const std::filesystem::path& folder, const DatasetInfo& dataset);

}  // namespace pixelcloth::data
