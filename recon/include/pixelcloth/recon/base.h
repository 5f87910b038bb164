#pragma once

// The learned refinement's inputs made by the marker pipeline (DESIGN.md, "Learned refinement"): for every row of a
// dataset, the base offsets that the spline cage and the anisotropic fill rebuild from that sample's own markers, and
// the marker features; written as a base folder (data/base_set.h).

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "pixelcloth/cage/length_model.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/recon/reconstruct.h"

namespace pixelcloth::recon {

/// The marker features of one frame: for each marker of `definition`, in its order, the captured position of the
/// marker of the same name in `captured` minus its vertex's embedded body point, in that point's frame (du, dv, dn,
/// metres: the transform of garment::offsetsFromPositions); 0 for a marker that `captured` lacks (dropped). `frames`
/// are the embedding's on the posed body (#V rows). Returns 3M values, marker by marker. Throws InputError for a
/// captured marker that `definition` does not have, or one out of its order.
Eigen::VectorXd markerFeatures(const cage::MarkerSet& definition, const cage::MarkerSet& captured,
                               const garment::EmbeddedFrames& frames);

/// Settings of writeDatasetBases: the same markers, capture, reconstruction and length model as
/// DatasetReconstructionOptions, with the method fixed to spline_anisotropic.
struct BaseSetOptions {
  cage::MarkerOptions markers;   ///< where the markers are
  cage::CaptureOptions capture;  ///< noise (metres) and dropout of the markers, seeded per sample
  ReconstructionOptions reconstruction;
  LengthModelSource lengthModel;  ///< overrides reconstruction.lengthModel
  cage::LengthModelOptions lengthModelFit;
  int threads = 1;  ///< samples rebuilt at once, in [1, 256]
  void validate() const;
};

/// What writeDatasetBases wrote.
struct BaseSetReport {
  int samples = 0;
  int markers = 0;              ///< M, markers per sample (dropped ones included, as zero features)
  double meanErrorCm = 0;       ///< mean per-vertex distance of the rebuilt garments from ground truth, cm
  double pushedOutPercent = 0;  ///< vertices moved out of the body (ReconstructionOptions::bodyClearance), percent
  double seconds = 0;
  /// "40 samples, 79 markers, spline_anisotropic: garment error 0.93 cm, 0.4% pushed out, 12.3 s".
  std::string summary() const;
};

/// For every row of the finished dataset `dataset` (all splits): markers from its ground truth (cage::defineMarkers,
/// then cage::placeMarkers with `options.capture` seeded per sample as reconstructDataset does), the garment rebuilt
/// from them by GarmentReconstructor with ReconstructionMethod::SplineAnisotropic (length model as
/// `options.lengthModel` says, fitted on the train split as reconstructDataset fits it), its offsets (those of the
/// final positions, after the body clearance) as base offsets, and markerFeatures of the captured markers. Writes the
/// base folder `out` (data::writeBaseSet) with settings: method, marker_spacing_m, marker_names (the definition's
/// order, that of the features), noise_cm, dropout, seed, body_clearance_m, rest_lengths, marker_sigma_m, anisotropic
/// and length_model ("none" or {"source", "samples", "model": the model as cage::toJson writes it}, so a new capture
/// can be rebuilt the same way). Progress on stderr. Throws InputError for a bad dataset folder or
/// options.
BaseSetReport writeDatasetBases(const data::DatasetFolder& dataset, const std::filesystem::path& out,
                                const BaseSetOptions& options = {});

}  // namespace pixelcloth::recon
