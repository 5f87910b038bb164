// What the dataset runs of recon/ share (reconstructDataset, writeDatasetBases): the reconstructor of a dataset, its
// rows' poses and captured markers, and the spline's length model.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "pixelcloth/cage/length_model.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/recon/reconstruct.h"

namespace pixelcloth::recon::detail {

/// A reconstructor over the dataset's own garment, body, embedding and rest positions.
std::unique_ptr<GarmentReconstructor> datasetReconstructor(const data::Dataset& dataset,
                                                           const ReconstructionOptions& options);

/// The pose of dataset row `row`.
body::Pose poseOfRow(const data::Dataset& dataset, int row);

/// The markers of `definition` captured from ground truth `truth` (#V x 3) of sample index `index`: noise and dropout
/// as `capture` says, seeded by its seed and the index, so each sample draws its own and the same sample always
/// draws the same, whichever other samples are rebuilt.
cage::MarkerSet captureMarkers(const cage::MarkerSet& definition, const Eigen::MatrixX3d& truth,
                               const cage::CaptureOptions& capture, int index);

/// Gives `reconstructor` the spline's length model of `lengthModel` (DatasetReconstructionOptions::lengthModel): one
/// fitted on the dataset's training split with `fit` (none when it has no training samples), none, or a length model
/// file, which must have been fitted at `markerSpacing`. Returns what the outputs record of it: "none", or
/// {"source", "samples"}.
nlohmann::json useLengthModel(GarmentReconstructor& reconstructor, const data::Dataset& dataset,
                              const cage::MarkerSet& definition, const LengthModelSource& lengthModel,
                              double markerSpacing, const cage::LengthModelOptions& fit);

}  // namespace pixelcloth::recon::detail
