#pragma once

// A motion through a trained model (the paper's Sec. 6 evaluation on motion capture) or through the marker
// reconstruction (Sec. 4, frame by frame): the garment of every frame written as an animated GLB, an OBJ sequence and
// PC2 caches, with the temporal measures. `predict --motion`, `reconstruct --markers-sequence` and the demo call it.

#include <filesystem>
#include <string>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/learn/prediction_inputs.h"
#include "pixelcloth/motion/motion.h"
#include "pixelcloth/motion/sequence.h"
#include "pixelcloth/motion/trajectories.h"
#include "pixelcloth/recon/reconstruct.h"
#include "pixelcloth/stitch/stitcher.h"

namespace pixelcloth::eval {

/// What a garment sequence is, as written and measured.
struct MotionPrediction {
  int frames = 0;
  double fps = 0;
  double predictSeconds = 0;  ///< making the garments (networks and stitching, or reconstruction), all frames
  motion::TemporalMetrics metrics;
  std::vector<Eigen::MatrixX3d> garment, body;  ///< per frame, in the body's root frame
  std::vector<std::string> files;               ///< written into the output folder, relative to it
};

/// Writes the garment sequence `garment` (per frame of `clip`, #G x 3 in the body's root frame; faces and UVs of
/// `garmentMesh`) on `body` posed as `poses` into `out`: animation.glb, frames/garment_NNNN.obj, garment.obj and
/// body.obj (frame 0), garment.pc2 and body.pc2 (the clip's root motion applied), metrics.json (the temporal measures
/// with `seamGapCm` per frame when some frame has one, `info` added). `predictSeconds` goes into the result and
/// metrics.json.
MotionPrediction writeGarmentSequence(const body::Body& body, const std::vector<body::Pose>& poses,
                                      const core::Mesh& garmentMesh, std::vector<Eigen::MatrixX3d> garment,
                                      std::vector<double> seamGapCm, double predictSeconds, const motion::Motion& clip,
                                      const std::filesystem::path& out, const nlohmann::json& info);

/// Predicts every frame of `clip` with `inputs` (learn::posesPredictionInputs of its poses, or a residual model's
/// with motionCaptureInputs' bases) and `stitcher`, and writes them with writeGarmentSequence, the seam gap of patch
/// models measured per frame.
MotionPrediction predictMotion(const learn::PredictionInputs& inputs, const stitch::Stitcher& stitcher,
                               const motion::Motion& clip, const std::filesystem::path& out,
                               const nlohmann::json& info = nlohmann::json::object());

/// The markers of `definition` on every frame of a garment sequence (`frames`, #V x 3 each), as a capture system sees
/// them: cage::placeMarkers with `capture`'s noise and dropout, seeded by its seed plus the frame, except that each
/// closed curve of `cage` keeps three markers (what its spline needs); NaN where dropped.
motion::MarkerTrajectories markerTrajectories(const cage::MarkerSet& definition, const cage::Cage& cage,
                                              const std::vector<Eigen::MatrixX3d>& frames,
                                              const cage::CaptureOptions& capture);

/// Each frame's captured markers in the body's root frame: `trajectories` (markers of `definition`, in its order, in
/// the clip's world: its root motion applied) with the root motion of `clip` undone about `rootPosition`, the markers
/// not seen in a frame (NaN) left out. Throws InputError naming the trajectory file, the frame and the curve when the
/// frames differ in number from the clip's, or when a frame leaves an open cage curve of `cage` without a marker at
/// one of its ends or a closed one with fewer than three.
std::vector<cage::MarkerSet> capturedFrames(const cage::MarkerSet& definition, const cage::Cage& cage,
                                            const motion::MarkerTrajectories& trajectories, const motion::Motion& clip,
                                            const Eigen::Vector3d& rootPosition);

/// The garment rebuilt by `reconstructor` from `captured` in every frame of `poses` by `method`, `threads` frames at
/// once (0: one per core); positions in the body's root frame. Progress on stderr; InputError naming `context` and
/// the frame when a frame cannot be solved.
std::vector<Eigen::MatrixX3d> reconstructFrames(const recon::GarmentReconstructor& reconstructor,
                                                const std::vector<cage::MarkerSet>& captured,
                                                const std::vector<body::Pose>& poses,
                                                recon::ReconstructionMethod method, int threads,
                                                const std::string& context);

/// A residual model's inputs for every frame of a capture: `inputs` (learn::posesPredictionInputs of the clip's
/// poses, for a residual model) completed with each frame's base, rebuilt from `captured` as the model's base folder
/// says (recon::CaptureRebuilder), and its marker features. `threads` frames at once (0: one per core).
void addCaptureBases(learn::PredictionInputs& inputs, const std::vector<cage::MarkerSet>& captured, int threads,
                     const std::string& context);

/// addCaptureBases of a capture's trajectories: `definition` (the marker file, named `markersName`) checked against
/// the model's garment, `trajectories` brought into the root frame of `body` (the model's dataset's) by capturedFrames.
/// Returns the seconds the bases took.
double addTrajectoryBases(learn::PredictionInputs& inputs, const body::Body& body, const cage::MarkerSet& definition,
                          const std::string& markersName, const motion::MarkerTrajectories& trajectories,
                          const motion::Motion& clip, int threads);

}  // namespace pixelcloth::eval
