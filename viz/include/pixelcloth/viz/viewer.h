#pragma once

// The browser viewer (DESIGN.md, viz/): an output folder as a static page that turns the garments around, overlays
// ground truth, colours errors, patches and cage curves, shows markers and plays sequences. index.html, the viewer's
// script, three.js copied from Debian's libjs-three, and one .glb per scene (with a .glb.js twin that the page loads,
// because a page opened from file:// may not fetch files). No server, no network.

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/garment/garment.h"

namespace pixelcloth::viz {

/// One garment of a scene: a prediction, a reconstruction method, or ground truth.
struct ViewGarment {
  std::string name;
  bool truth = false;                    ///< ground truth, which the other garments are compared with
  std::vector<Eigen::MatrixX3d> frames;  ///< per frame #V x 3, metres (one for a still scene)
  Eigen::VectorXd errorCm;               ///< optional #V: distance to ground truth, cm
};

/// A cage curve drawn over the scene's first garment, coloured by `normalJumpDeg`.
struct ViewCurve {
  std::string name;
  std::vector<int> vertices;  ///< garment vertices along the curve; consecutive ones joined where they share an edge
  double normalJumpDeg = 0;
};

/// What one entry of the page's scene list shows.
struct ViewScene {
  std::string name;
  std::string group;  ///< heading of the scene list the entry sits under
  Eigen::MatrixX3i bodyFaces;
  std::vector<Eigen::MatrixX3d> bodyFrames;  ///< per frame, or one; empty: no body
  Eigen::MatrixX3i garmentFaces;
  std::vector<ViewGarment> garments;
  Eigen::VectorXi patchOfVertex;  ///< optional #V: each garment vertex's patch (its first)
  std::vector<ViewCurve> curves;
  /// What normalJumpDeg measures: "normal jump" (|fold angle - ground truth's| across the curve) or "fold angle".
  std::string curveMeasure = "normal jump";
  std::vector<Eigen::MatrixX3d> markers;  ///< per frame, or one: M x 3, a NaN row where a marker is not seen
  double fps = 30;
  nlohmann::json info = nlohmann::json::object();  ///< figures listed beside the view
};

struct ViewSite {
  std::string title;
  std::string source;  ///< the folder it shows
  std::vector<ViewScene> scenes;
};

/// The colour scales of the page and its legends: errors from 0 to 1 cm (as error_maps.png), cage curves from 0 to
/// 10 degrees.
constexpr double kViewErrorScaleCm = 1.0;
constexpr double kViewCurveScaleDeg = 10.0;

/// The cage curves of `garment` with the fold angle of `shown` across each (mean over its two-sided edges) or, with
/// `truth`, its normal jump against ground truth (stitch::SeamMetrics' measure).
std::vector<ViewCurve> viewCurves(const garment::Garment& garment, const Eigen::MatrixX3d& shown,
                                  const Eigen::MatrixX3d* truth);

/// Each garment vertex's patch (the lowest id of the patches that hold it).
Eigen::VectorXi patchOfVertex(const garment::Garment& garment);

/// Where libjs-three's files are: $PIXELCLOTH_THREE_DIR, else /usr/share/javascript/three. Throws InputError naming
/// the missing file and the package when three.min.js, GLTFLoader.js or OrbitControls.js is not there.
std::filesystem::path threeJsFolder();

/// Writes `site` into `out` (created if missing): index.html, viewer.js, site.js (the scene list), three/, and
/// scenes/NNN.glb with scenes/NNN.glb.js per scene. Every file is written atomically. Progress on stderr.
void writeViewSite(const std::filesystem::path& out, const ViewSite& site);

struct ViewOptions {
  int maxScenes = 24;  ///< samples of a dataset or an evaluation shown, spread over its rows
};

/// The scenes of an output folder, whichever verb wrote it: a dataset (`generate`, `dataset import`), `evaluate`,
/// `predict` (a pose or samples), `reconstruct --dataset` (every method against ground truth), a sequence (`predict
/// --motion`, `reconstruct --markers-sequence`), or a folder holding several of these (the demo's report). Throws
/// InputError naming the folder and what was expected when it is none of them.
ViewSite viewFolder(const std::filesystem::path& folder, const ViewOptions& options = {});

}  // namespace pixelcloth::viz
