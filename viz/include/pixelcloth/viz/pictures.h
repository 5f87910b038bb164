#pragma once

// The pictures of each stage, drawn from its plain results (a stage's library never draws).

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/cage/cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/data/face_statistics.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/patches/cloth_image.h"
#include "pixelcloth/recon/reconstruct.h"

namespace pixelcloth::viz {

/// Picture of the flat pattern for people: the layouts side by side (in `layouts` order) with a gap, panels tinted by
/// panel, triangle edges thin grey, seams thick, each seam in its own colour (the same on both layouts), openings
/// dark, cage lines dark blue. `pixelsPerMetre` of pattern space (10 to 10000).
core::RgbImage renderPattern(const garment::Garment& garment, int pixelsPerMetre = 1000);

/// Picture of a cage on its mesh: front, back and three-quarter views, curves coloured by kind (loops red,
/// centre lines blue, seams green, openings black, splits orange), nodes as dots; only parts facing the camera drawn.
core::RgbImage renderCageOnMesh(const core::Mesh& mesh, const cage::Cage& cage, int panelSize = 420);

/// How renderFacePanels colours a face's value.
enum class FaceScale {
  AreaRatio,  ///< an area ratio: log2 from -1 (blue, half the area or less) through 0 (white) to 1 (red, twice)
  Fraction,   ///< a fraction: white (0) to red (the largest of the panels, at least 1%, rounded up)
};

/// One panel of renderFacePanels: a value per garment face.
struct FacePanel {
  std::string title;
  Eigen::VectorXd values;
};

/// Per-face values of `garment` in pattern space, 1 to 4 panels side by side (each its layouts labelled: front, back,
/// sleeves), each with a line of statistics, and a colour bar.
core::RgbImage renderFacePanels(const garment::Garment& garment, const std::vector<FacePanel>& panels, FaceScale scale,
                                int pixelsPerMetre = 800);

/// Area distortion in pattern space, before and after relaxation side by side: faces coloured by
/// log2(3D area / pattern area), red for stretch, blue for compression, white for none; with a colour bar.
core::RgbImage renderAreaDistortion(const garment::Garment& garment, const cage::Dressing& dressing,
                                    int pixelsPerMetre = 800);

/// How PNG previews show a cloth image.
struct PreviewOptions {
  /// Offsets in [-range, range] (metres) map to [0, 255] per channel (0 -> 128); 0: per channel, the largest |value|
  /// over the non-empty pixels of every layer (at least 1e-6).
  float range = 0;
  float paddingBrightness = 0.55f;  ///< padding pixels are this fraction of their colour (dimmer), in [0, 1]
};

/// PNG preview in the paper's style: RGB = (du, dv, dn) mapped symmetrically around 0 to [0, 255], padding dimmer,
/// empty pixels white; layers side by side left to right in `layers` order, no gap (so pixel (x, y) of layer l is
/// preview pixel (l * width + x, y)).
core::RgbImage renderClothImage(const patches::ClothImage& image, const PreviewOptions& options = {});

/// Writes a folder of posed bodies: posed_NNN.obj per pose, poses.npy (N x 90 float32), poses.json (each pose
/// as poseToJson plus its mesh name, and `info` at the top level) and posed.png (up to 24 poses at one scale,
/// skeletons drawn). Shows progress on stderr.
void writePosedBodies(const std::filesystem::path& folder, const body::Body& body, const std::vector<body::Pose>& poses,
                      const nlohmann::json& info = nlohmann::json::object());

/// The body in `count` frames of a pose sequence spread evenly from the first to the last, side by side on one scale,
/// each labelled with its frame and time at `fps` (a motion clip's strip).
core::RgbImage renderPoseStrip(const body::Body& body, const std::vector<body::Pose>& poses, double fps, int count = 8);

/// Per-vertex values (#V, e.g. errors in metres) drawn in pattern space: each layout in its own `size` x `size`
/// cloth-image frame, faces coloured by the mean of their vertices on a dark-blue-to-yellow ramp from 0 to `maxValue`
/// (`blueToRed`: blue, white, red), under a title row. Layouts side by side.
core::RgbImage renderPatternValues(const garment::Garment& garment, const Eigen::VectorXd& values, double maxValue,
                                   const std::string& title, int size = 256, bool blueToRed = false);

/// The error maps of reconstructDataset's methods, one row each on one colour scale (the largest mean vertex error of
/// any method, at least 1 cm), titled with the method and its mean error.
core::RgbImage renderReconstructionErrors(const garment::Garment& garment,
                                          const recon::DatasetReconstructionReport& report);

/// Writes cage.json, patches.json and cage.png of a garment into `out` (the `cage` verb's outputs; the demo's too).
void writeCageFolder(const garment::Garment& garment, const std::filesystem::path& out, int size = 512);

/// Writes the `dress` verb's outputs for a garment dressed on `body` into `out`, each file atomically: dressed.obj
/// (the relaxed positions with the garment's UVs), area_distortion.png (viz::renderAreaDistortion), dressed.png (the
/// dressed garment on the body, three views) and dressing.json (iterations, residual, area-ratio statistics before and
/// after relaxation, vertices pushed out and their deepest penetration, vertices still inside, vertices per part).
void writeDressingFolder(const body::Body& body, const garment::Garment& garment, const cage::Dressing& dressing,
                         const std::filesystem::path& out);

/// Writes a dataset's appendix statistics (data::faceStatistics of the dataset at `source`) into `out`, each file
/// atomically: area_distortion.png (per face, the smallest and the largest area ratio over the samples),
/// self_intersection.png (per face, the fraction of samples in which it passes through the garment) and
/// face_statistics.json (those numbers per face, and the samples with any self-intersection).
void writeFaceStatistics(const garment::Garment& garment, const data::FaceStatistics& stats,
                         const std::filesystem::path& source, const std::filesystem::path& out);

/// Training curves of a learn::NetworkReport: per-vertex error (cm, log scale) on the train split (blue) and the
/// regularisation split (orange), against the epoch (left) and against the wall time of the epochs (right), the best
/// epoch marked in both, under a title naming `model`. At least 400 x 150.
core::RgbImage renderTrainingCurves(const learn::NetworkReport& report, const std::string& model, int width = 960,
                                    int height = 360);

}  // namespace pixelcloth::viz
