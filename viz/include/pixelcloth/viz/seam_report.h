#pragma once

// The seam report of one model (DESIGN.md, "Stitching"): every stitch mode's errors and seam figures as tables, the PCA
// filter's k sweep as a plot, per-vertex error maps, a table per cage curve, and example garments with their worst
// seams marked; report.md with its PNGs beside it.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/stitch/evaluate.h"

namespace pixelcloth::viz {

/// One example garment of the report: a sample as one stitch mode made it, with its ground truth and posed body.
struct SeamExample {
  std::string label;           ///< e.g. "sample 431, mean"
  Eigen::MatrixX3d positions;  ///< #V x 3
  Eigen::MatrixX3d truth;      ///< #V x 3
  body::Body body;             ///< posed
};

struct SeamReportInputs {
  std::string title;       ///< e.g. "patch_pose_zero on tshirt480, test split"
  std::string command;     ///< the command that made it, shown verbatim
  garment::Garment garment;
  std::vector<stitch::Evaluation> evaluations;  ///< one per stitch mode, the plain mean first when measured
  std::vector<SeamExample> examples;
  std::string extra;  ///< Markdown appended after the stitch-mode table (e.g. the demo's tables in the paper's form)
};

/// Mean vertex error and normal jump against k for the pca:K modes among `evaluations` (at least two), beside the
/// plain mean's as dashed lines, the chosen k (lowest vertex error) marked.
core::RgbImage renderPcaSweep(const std::vector<stitch::Evaluation>& evaluations, int width = 720, int height = 300);

/// A garment on its body, front and back, coloured by per-vertex error (0 to `maxErrorCm`), the three cage curves
/// with the largest normal jump against ground truth drawn over it and named.
core::RgbImage renderWorstSeams(const garment::Garment& garment, const SeamExample& example, double maxErrorCm,
                                int panelSize = 360);

/// A JSON number as text with `digits` decimals, "-" for null (a figure that does not apply): for tables and logs.
std::string figureText(const nlohmann::json& value, int digits = 3);

/// Writes report.md, pca_sweep.png (with two or more pca modes), error_maps_by_mode.png and worst_seams.png (with
/// examples) into `folder` (created), each atomically.
void writeSeamReport(const std::filesystem::path& folder, const SeamReportInputs& inputs);

}  // namespace pixelcloth::viz
