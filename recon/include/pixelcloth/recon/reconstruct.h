#pragma once

// Garments from sparse markers: the cage from the spline solver (cage/), its offsets in the posed body's embedded
// frames (garment/), every patch interior filled from its boundary (patches/), back to positions; and the evaluation
// of the methods on a dataset (data/).

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/cage/length_model.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/cage/spline_solver.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/basis.h"

namespace pixelcloth::recon {

/// The methods of the spline solver's comparison (DESIGN.md, "Key-point-to-cage spline solver"): cage curves drawn
/// linearly, by Catmull-Rom, or by the length-preserving spline, with patch interiors filled by isotropic harmonic
/// bases; and the spline with anisotropic bases.
enum class ReconstructionMethod { Linear, CatmullRom, Spline, SplineAnisotropic };

/// "linear", "catmull_rom", "spline", "spline_anisotropic".
const char* reconstructionMethodName(ReconstructionMethod method);
ReconstructionMethod reconstructionMethodFromName(const std::string& name, const std::string& context);
/// All four, in the order above.
std::vector<ReconstructionMethod> allReconstructionMethods();

/// Settings of the reconstruction.
struct ReconstructionOptions {
  cage::SplineOptions spline;  ///< the curve solver (its `method` is overridden per ReconstructionMethod)
  /// The anisotropic fill of SplineAnisotropic: diffusion faster along the pattern's u axis (theta = 0: around the
  /// body) than along v, ratio 0.6 (reach about 1.3 times further). Chosen on a 40-sample T-shirt dataset (seed 7):
  /// u beat v at every ratio tried (0.3-0.8), and 0.6 was the best ratio (garment error 1.09 cm, isotropic 1.11,
  /// v at 0.3 1.26).
  patches::BasisOptions anisotropic{true, 0.0, 0.6};
  /// The worn lengths the spline's segments are held to (cage/length_model.h), e.g. fitted on a dataset's training
  /// split; none: at least their rest lengths.
  std::optional<cage::LengthModel> lengthModel;
  /// Every rebuilt vertex inside the posed body, or nearer its surface than this, is moved to this distance from its
  /// closest surface point (metres; < 0: never). Nothing else keeps the filled interiors out of the body. Chosen on
  /// the regularisation split of a 200-sample T-shirt dataset (0, 1, 2, 3 mm: garment error of spline_anisotropic
  /// 0.921, 0.917, 0.922, 0.934 cm; 0.951 without); the simulated shirts have 0.5% of their vertices inside the body.
  /// The whole body counts, not only a vertex's own collision part as in the simulator, so a sleeve that the
  /// simulator let sink into the torso comes out of it here; a marker nearer the body than this moves too.
  double bodyClearance = 0.001;
  void validate() const;
};

/// One frame's posed body: its vertices, the frames of the cloth pixels' embedding on it, and a search tree over its
/// surface (CGAL AABB) for ReconstructionOptions::bodyClearance; built once per frame, shared by every method.
class PosedBody {
 public:
  PosedBody(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, garment::EmbeddedFrames frames);
  ~PosedBody();
  PosedBody(PosedBody&&) noexcept;

  const garment::EmbeddedFrames& frames() const;
  /// Moves every row of `points` that is inside the body (behind the smooth normal at its closest surface point) or
  /// nearer the surface than `clearance` to `clearance` from that closest point: along the normal from inside, straight
  /// away from it from outside. Returns how many moved.
  int pushOut(Eigen::MatrixX3d& points, double clearance) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One garment rebuilt from markers.
struct Reconstruction {
  Eigen::MatrixX3d cage;       ///< #V x 3: the cage vertices' positions from the curves; NaN elsewhere
  Eigen::MatrixX3d offsets;    ///< #V x 3: cage offsets, interiors filled (du, dv, dn; metres)
  Eigen::MatrixX3d positions;  ///< #V x 3: the garment, metres
  int pushedOut = 0;           ///< vertices moved out of the body (ReconstructionOptions::bodyClearance)
  cage::SplineSummary spline;
};

/// Everything that stays the same from frame to frame: the garment's cage and its spline solver (rest lengths), the
/// patches' bases (built on first use: isotropic and anisotropic), the body and the embedding of the cloth pixels.
class GarmentReconstructor {
 public:
  /// `embedding` of the garment's #V cloth pixels on `body`; `restPositions` (#V x 3, the dressed garment) for
  /// polyline or geodesic rest lengths. Throws InputError for sizes that disagree or invalid options.
  GarmentReconstructor(const body::Body& body, const garment::Garment& garment, const garment::Embedding& embedding,
                       const Eigen::MatrixX3d& restPositions, const ReconstructionOptions& options = {});
  ~GarmentReconstructor();
  GarmentReconstructor(const GarmentReconstructor&) = delete;
  GarmentReconstructor& operator=(const GarmentReconstructor&) = delete;

  /// Rebuilds the garment worn in `pose` from `markers` (positions required; checked against the garment and cage,
  /// and each within kMaxMarkerDistance of where its vertex rests on the posed body). `context` (a file name) starts
  /// the messages.
  Reconstruction reconstruct(const cage::MarkerSet& markers, const body::Pose& pose,
                             ReconstructionMethod method = ReconstructionMethod::Spline,
                             const std::string& context = "markers") const;
  /// The same on a posed body made once for the frame (`posed`), to share it between methods.
  Reconstruction reconstruct(const cage::MarkerSet& markers, const PosedBody& body, ReconstructionMethod method,
                             const std::string& context = "markers") const;

  /// How far a marker may be from where its garment vertex rests on the posed body (the embedding's point), metres:
  /// a garment hangs centimetres from the body, never a metre; beyond it the markers are in other units or of
  /// another pose.
  static constexpr double kMaxMarkerDistance = 1.0;
  /// The procedural fill alone: cage positions (#V x 3, only cage rows read) -> offsets -> every patch's interior ->
  /// positions (kept ReconstructionOptions::bodyClearance out of the body).
  Reconstruction fillFromCage(const Eigen::MatrixX3d& cagePositions, const PosedBody& body, bool anisotropic) const;
  /// Replaces ReconstructionOptions::lengthModel (InputError naming `context` when it does not fit the garment).
  void setLengthModel(std::optional<cage::LengthModel> model, const std::string& context = "length model");
  /// The body posed by `pose`, with the frames of the embedding on it.
  PosedBody posed(const body::Pose& pose) const;

  const garment::Garment& garment() const;
  const cage::Cage& cage() const;
  const cage::CageSplineSolver& solver() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Where the spline's worn-length model (the paper's Sec. 4.1 arc lengths, learned) comes from on a dataset.
struct LengthModelSource {
  enum class Kind {
    Fit,   ///< fitted on the dataset's train split (with no training samples: none)
    None,  ///< rest lengths
    File   ///< a length model file an earlier run wrote
  };
  Kind kind = Kind::Fit;
  std::filesystem::path file;  ///< Kind::File

  static LengthModelSource fit() { return {}; }
  static LengthModelSource none() { return {Kind::None, {}}; }
  static LengthModelSource fromFile(std::filesystem::path path) { return {Kind::File, std::move(path)}; }
};

/// Settings of reconstructDataset.
struct DatasetReconstructionOptions {
  std::optional<data::Split> split = data::Split::Test;  ///< the rows rebuilt; none: every row
  cage::MarkerOptions markers;   ///< where the markers are
  cage::CaptureOptions capture;  ///< noise (metres) and dropout of the markers, seeded per sample
  ReconstructionOptions reconstruction;
  int meshes = 3;  ///< the first this many samples are written as OBJ (truth and each method)
  /// The spline's length model (a fitted one is written to length_model.json). Overrides reconstruction.lengthModel.
  LengthModelSource lengthModel;
  cage::LengthModelOptions lengthModelFit;
  void validate() const;
};

/// What reconstructDataset measured.
struct DatasetReconstructionReport {
  /// {"dataset", "split", "samples", "markers", "noise_cm", "dropout", "seconds",
  ///  "methods": {name: {"cage_cm", "garment_cm", "max_garment_cm", "curve_length_error_cm", "pushed_out_percent",
  ///                     "curves": {curve: {"position_error_cm", "length_error_cm", "length_error_percent"}}}}}:
  /// mean per-vertex errors in cm over the split (cage vertices; all vertices), and per curve the mean per-vertex error
  /// and the mean |length of the reconstructed cage polyline - ground truth's|.
  nlohmann::json metrics;
  std::vector<Eigen::VectorXd> meanVertexError;  ///< per method (allReconstructionMethods order): #V, metres
  int samples = 0;
};

/// Reconstructs every sample of one split of a finished dataset folder from markers taken from its ground truth, by
/// every method, and writes into `out`: metrics.json, markers.json (the marker definition), length_model.json (when one
/// is used) and OBJs of the first few samples (sample_NNNNNN/truth.obj, <method>.obj); the error maps are viz's
/// (viz::renderReconstructionErrors of the report). Progress on stderr. Throws InputError for a bad
/// folder, an empty split or options.
DatasetReconstructionReport reconstructDataset(const data::DatasetFolder& dataset, const std::filesystem::path& out,
                                               const DatasetReconstructionOptions& options = {});

}  // namespace pixelcloth::recon
