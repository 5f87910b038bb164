#pragma once

// The residual models' base for a new capture (pixelcloth predict --pose P --markers M): the garment rebuilt from the
// captured markers exactly as a base folder's samples were (its manifest's settings), and their marker features.

#include <Eigen/Core>
#include <filesystem>
#include <memory>

#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/recon/reconstruct.h"

namespace pixelcloth::recon {

struct CaptureBase {
  Eigen::MatrixX3d offsets;  ///< #V x 3 base offsets (du, dv, dn) in the posed body's frames
  Eigen::VectorXd features;  ///< 3M marker features, in the base folder's marker order
};

/// The way a base folder's samples were rebuilt, read once from `baseFolder`/manifest.json (marker spacing and names,
/// body clearance, rest lengths, anisotropy, length model), to rebuild new captures of the dataset `dataset` the same
/// way: one pose (predict --pose --markers) or every frame of a marker sequence. `rebuild` may run on several threads.
class CaptureRebuilder {
 public:
  /// Throws InputError naming the file for a base folder of another dataset or settings that do not fit its garment.
  CaptureRebuilder(const std::filesystem::path& baseFolder, const data::DatasetFolder& dataset);
  ~CaptureRebuilder();
  CaptureRebuilder(const CaptureRebuilder&) = delete;
  CaptureRebuilder& operator=(const CaptureRebuilder&) = delete;

  /// The base of `captured` (positions required) worn in `pose`, by spline_anisotropic; InputError naming
  /// `markersContext` for markers that do not fit the garment or the base folder's.
  CaptureBase rebuild(const cage::MarkerSet& captured, const body::Pose& pose, const std::string& markersContext) const;
  /// The base folder's markers, in the order of the features.
  const cage::MarkerSet& definition() const;
  const GarmentReconstructor& reconstructor() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Rebuilds the garment of the dataset `dataset` worn in `pose` from `captured` (positions required) with the
/// settings recorded in `baseFolder`/manifest.json (marker spacing and names, body clearance, rest lengths, anisotropy,
/// length model), by spline_anisotropic, as writeDatasetBases did for the dataset's samples. Throws InputError naming
/// the file for a base folder of another dataset, or markers that do not fit the garment or the base folder's.
CaptureBase baseOfCapture(const std::filesystem::path& baseFolder, const data::DatasetFolder& dataset,
                          const cage::MarkerSet& captured, const body::Pose& pose, const std::string& markersContext);

}  // namespace pixelcloth::recon
