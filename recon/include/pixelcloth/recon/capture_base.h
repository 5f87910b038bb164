#pragma once

// The residual models' base for a new capture (pixelcloth predict --pose P --markers M): the garment rebuilt from the
// captured markers exactly as a base folder's samples were (its manifest's settings), and their marker features.

#include <Eigen/Core>
#include <filesystem>

#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/data/dataset.h"

namespace pixelcloth::recon {

struct CaptureBase {
  Eigen::MatrixX3d offsets;  ///< #V x 3 base offsets (du, dv, dn) in the posed body's frames
  Eigen::VectorXd features;  ///< 3M marker features, in the base folder's marker order
};

/// Rebuilds the garment of the dataset `dataset` worn in `pose` from `captured` (positions required) with the
/// settings recorded in `baseFolder`/manifest.json (marker spacing and names, body clearance, rest lengths, anisotropy,
/// length model), by spline_anisotropic, as writeDatasetBases did for the dataset's samples. Throws InputError naming
/// the file for a base folder of another dataset, or markers that do not fit the garment or the base folder's.
CaptureBase baseOfCapture(const std::filesystem::path& baseFolder, const data::DatasetFolder& dataset,
                          const cage::MarkerSet& captured, const body::Pose& pose, const std::string& markersContext);

}  // namespace pixelcloth::recon
