// The seam report of one model: tables of every stitch mode, the PCA filter's k sweep, error maps, a table per cage
// curve and example garments with their worst seams marked.
#include "pixelcloth/viz/seam_report.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/stitch/seams.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

namespace fs = std::filesystem;

namespace {

/// The k of a "pca:K" mode; 0 for other modes.
int pcaComponents(const stitch::Evaluation& e) {
  return e.mode.kind == stitch::StitchKind::Pca ? e.mode.components : 0;
}

const stitch::Evaluation* meanMode(const std::vector<stitch::Evaluation>& evaluations) {
  for (const stitch::Evaluation& e : evaluations)
    if (e.mode.kind == stitch::StitchKind::Mean) return &e;
  return nullptr;
}

/// A dashed horizontal line.
void dashed(core::RgbImage& image, double x0, double x1, double y, core::Color color) {
  for (double x = x0; x < x1; x += 10) drawLine(image, {x, y}, {std::min(x + 5, x1), y}, color, 1.5);
}

/// One panel of the sweep: `values` against log2 k, with the mean's value dashed.
void sweepPanel(core::RgbImage& image, int left, int right, int top, int bottom, const std::vector<int>& ks,
                const std::vector<double>& values, double meanValue, int chosen, const std::string& title,
                core::Color color) {
  const core::Color black = {30, 30, 30}, grey = {205, 205, 205}, dark = {90, 90, 90};
  double hi = meanValue;
  for (double v : values) hi = std::max(hi, v);
  hi = hi > 0 ? 1.1 * hi : 1;
  const double kLo = std::log2(ks.front()), kHi = std::max(kLo + 1, std::log2(ks.back()));
  auto at = [&](int k, double v) {
    return Eigen::Vector2d(left + (std::log2(k) - kLo) / (kHi - kLo) * (right - left), bottom - v / hi * (bottom - top));
  };
  for (int tick = 0; tick <= 4; ++tick) {
    const double v = hi * tick / 4, y = bottom - tick / 4.0 * (bottom - top);
    drawLine(image, {left, y}, {right, y}, grey);
    std::ostringstream label;
    label << std::setprecision(3) << v;
    drawText(image, {left - 44, static_cast<int>(y) - 3}, label.str(), black);
  }
  for (int k : ks) {
    const Eigen::Vector2d p = at(k, 0);
    drawText(image, {static_cast<int>(p.x()) - 6, bottom + 6}, std::to_string(k), black);
  }
  drawText(image, {left, top - 30}, title, black, 2);
  dashed(image, left, right, at(ks.front(), meanValue).y(), dark);
  drawText(image, {right - textExtent("plain mean").x(), static_cast<int>(at(ks.front(), meanValue).y()) - 12},
           "plain mean", dark);
  for (size_t i = 1; i < ks.size(); ++i) drawLine(image, at(ks[i - 1], values[i - 1]), at(ks[i], values[i]), color, 2);
  for (size_t i = 0; i < ks.size(); ++i) drawDisc(image, at(ks[i], values[i]), ks[i] == chosen ? 5 : 2.5, color);
}

}  // namespace

std::string figureText(const nlohmann::json& value, int digits) {
  if (!value.is_number()) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value.get<double>();
  return out.str();
}

core::RgbImage renderPcaSweep(const std::vector<stitch::Evaluation>& evaluations, int width, int height) {
  std::vector<std::pair<int, const stitch::Evaluation*>> sweep;
  for (const stitch::Evaluation& e : evaluations)
    if (pcaComponents(e) > 0) sweep.emplace_back(pcaComponents(e), &e);
  PIXELCLOTH_CHECK(sweep.size() >= 2, "pca sweep: " << sweep.size() << " pca:K modes, expected two or more");
  std::sort(sweep.begin(), sweep.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<int> ks;
  std::vector<double> error, jump;
  for (const auto& [k, e] : sweep) {
    ks.push_back(k);
    error.push_back(e->metrics["vertex_error_cm"].get<double>());
    jump.push_back(e->metrics["seams"]["normal_jump_deg"].is_number() ? e->metrics["seams"]["normal_jump_deg"].get<double>()
                                                                       : 0.0);
  }
  const stitch::Evaluation* mean = meanMode(evaluations);
  const double meanError = mean ? mean->metrics["vertex_error_cm"].get<double>() : 0,
               meanJump = mean && mean->metrics["seams"]["normal_jump_deg"].is_number()
                              ? mean->metrics["seams"]["normal_jump_deg"].get<double>()
                              : 0;
  const int best = stitch::bestPcaMode(evaluations);
  const int chosen = best >= 0 ? pcaComponents(evaluations[best]) : 0;
  core::RgbImage image(width, height);
  const int half = width / 2;
  sweepPanel(image, 56, half - 16, 50, height - 40, ks, error, meanError, chosen, "vertex error (cm)", {40, 100, 200});
  sweepPanel(image, half + 56, width - 16, 50, height - 40, ks, jump, meanJump, chosen, "normal jump (deg)",
             {230, 120, 20});
  drawText(image, {56, height - 16}, "k: principal components kept (log scale); large dot: the k of lowest error",
           {30, 30, 30});
  return image;
}

core::RgbImage renderWorstSeams(const garment::Garment& garment, const SeamExample& example, double maxErrorCm,
                                int panelSize) {
  const stitch::SeamLayout layout(garment);
  stitch::SeamMetrics metrics(layout);
  metrics.add({}, example.positions, example.truth);
  const nlohmann::json curves = metrics.toJson()["curves"];
  std::vector<std::pair<double, size_t>> ranked;
  for (size_t c = 0; c < curves.size(); ++c)
    if (curves[c]["normal_jump_deg"].is_number()) ranked.emplace_back(curves[c]["normal_jump_deg"].get<double>(), c);
  std::sort(ranked.rbegin(), ranked.rend());
  ranked.resize(std::min<size_t>(3, ranked.size()));

  const Eigen::VectorXd error = 100 * (example.positions - example.truth).rowwise().norm();
  RenderMesh cloth{example.positions, garment.mesh.F, Eigen::MatrixX3d(error.size(), 3), {}, {0.8, 0.8, 0.8}};
  for (Eigen::Index v = 0; v < error.size(); ++v)
    cloth.vertexColors.row(v) = colorRamp(std::min(1.0, error(v) / std::max(1e-9, maxErrorCm))).transpose();
  const RenderMesh skin{example.body.mesh.V, example.body.mesh.F, {}, {}, {0.87, 0.78, 0.70}};
  const Eigen::MatrixX3d normals = core::vertexNormals(example.positions, garment.mesh.F);
  std::vector<core::RgbImage> panels;
  for (double azimuth : {0.0, 180.0}) {
    View view;
    view.azimuthDegrees = azimuth;
    view.width = view.height = panelSize;
    view.bounds.extend(example.positions.colwise().minCoeff().transpose());
    view.bounds.extend(example.positions.colwise().maxCoeff().transpose());
    Projection projection;
    core::RgbImage picture = renderMeshes({cloth, skin}, view, &projection);
    const Eigen::Vector3d towardsViewer = projection.rotation.row(2).transpose();
    for (size_t r = 0; r < ranked.size(); ++r) {
      const stitch::SeamCurve& curve = layout.curves()[ranked[r].second];
      for (int v : curve.vertices)
        if (normals.row(v).dot(towardsViewer) > 0)
          drawDisc(picture, projection.toPixel(example.positions.row(v).transpose()), 3, paletteColor(static_cast<int>(r)));
    }
    drawText(picture, {8, 8}, example.label + (azimuth == 0 ? ", front" : ", back"), {0, 0, 0}, 2);
    panels.push_back(std::move(picture));
  }
  core::RgbImage sheet = contactSheet(panels, 2);
  core::RgbImage out(sheet.width, sheet.height + 22 * static_cast<int>(ranked.size()) + 8);
  paste(out, sheet, 0, 0);
  for (size_t r = 0; r < ranked.size(); ++r) {
    std::ostringstream line;
    line << std::fixed << std::setprecision(1) << curves[ranked[r].second]["name"].get<std::string>()
         << ": normal jump " << ranked[r].first << " deg";
    drawText(out, {12, sheet.height + 6 + 22 * static_cast<int>(r)}, line.str(), paletteColor(static_cast<int>(r)), 2);
  }
  return out;
}

void writeSeamReport(const fs::path& folder, const SeamReportInputs& inputs) {
  PIXELCLOTH_CHECK(!inputs.evaluations.empty(), "seam report: no evaluations");
  core::ensureOutputFolder(folder);
  const std::vector<stitch::Evaluation>& evaluations = inputs.evaluations;
  const stitch::Evaluation* mean = meanMode(evaluations);
  const int best = stitch::bestPcaMode(evaluations);
  std::ostringstream md;
  md << "# Seams: " << inputs.title << "\n\n";
  if (!inputs.command.empty()) md << "```sh\n" << inputs.command << "\n```\n\n";
  const nlohmann::json& first = evaluations.front().metrics;
  md << first["samples"].get<int>() << " samples of the " << first["split"].get<std::string>()
     << " split. Vertex error: mean per-vertex distance to ground truth. Gap: before blending, the largest distance "
        "between two networks' predictions of a cage vertex. Normal jump: after blending, |fold angle across a cage "
        "edge - ground truth's|. Near seams: vertices within two rings of a curve patches meet across.\n\n";
  md << "| stitch | vertex error (cm) | normal cosine distance | gap mean (cm) | gap max (cm) | normal jump (deg) | "
        "error near seams (cm) | interior (cm) |\n|---|---|---|---|---|---|---|---|\n";
  for (const stitch::Evaluation& e : evaluations) {
    const nlohmann::json& m = e.metrics;
    const nlohmann::json& s = m["seams"];
    md << "| " << m["stitch"].get<std::string>() << " | " << figureText(m["vertex_error_cm"]) << " | "
       << figureText(m["normal_cosine_distance"], 4) << " | " << figureText(s["gap_cm"]["mean"]) << " | "
       << figureText(s["gap_cm"]["max"]) << " | " << figureText(s["normal_jump_deg"], 2) << " | "
       << figureText(s["near_seam_error_cm"]) << " | " << figureText(s["interior_error_cm"]) << " |\n";
  }
  if (first["base_vertex_error_cm"].is_number())
    md << "\nThe marker reconstruction alone (the residual model's base): " << figureText(first["base_vertex_error_cm"])
       << " cm.\n";
  if (!inputs.extra.empty()) md << "\n" << inputs.extra << "\n";
  int sweepModes = 0;
  for (const stitch::Evaluation& e : evaluations) sweepModes += pcaComponents(e) > 0;
  if (sweepModes >= 2) {
    core::writePng(folder / "pca_sweep.png", renderPcaSweep(evaluations));
    md << "\n## PCA filter: the sweep of k\n\n![](pca_sweep.png)\n\n";
    if (best >= 0 && mean) {
      const nlohmann::json& b = evaluations[best].metrics;
      const double error = b["vertex_error_cm"].get<double>() / mean->metrics["vertex_error_cm"].get<double>() - 1;
      md << "Lowest vertex error at " << b["stitch"].get<std::string>() << ": " << figureText(b["vertex_error_cm"])
         << " cm (" << std::showpos << std::fixed << std::setprecision(1) << 100 * error << std::noshowpos
         << "% against the plain mean)";
      if (b["seams"]["normal_jump_deg"].is_number() && mean->metrics["seams"]["normal_jump_deg"].is_number()) {
        const double jump =
            b["seams"]["normal_jump_deg"].get<double>() / mean->metrics["seams"]["normal_jump_deg"].get<double>() - 1;
        md << ", normal jump " << figureText(b["seams"]["normal_jump_deg"], 2) << " deg (" << std::showpos << std::fixed
           << std::setprecision(1) << 100 * jump << std::noshowpos << "%)";
      }
      md << ". Choose k on the regularisation split and report the test split at that k.\n";
    }
  }
  // Per curve: the plain mean and the best filter side by side.
  const stitch::Evaluation& left = mean ? *mean : evaluations.front();
  const stitch::Evaluation* right = best >= 0 ? &evaluations[best] : nullptr;
  md << "\n## Per cage curve\n\n| curve | kind | vertices | shared | gap mean (cm) | gap max (cm) | normal jump, "
     << left.metrics["stitch"].get<std::string>() << " (deg)";
  if (right) md << " | normal jump, " << right->metrics["stitch"].get<std::string>() << " (deg)";
  md << " | error near it, " << left.metrics["stitch"].get<std::string>() << " (cm)";
  if (right) md << " | error near it, " << right->metrics["stitch"].get<std::string>() << " (cm)";
  md << " |\n|---|---|---|---|---|---|---|---|" << (right ? "---|---|" : "") << "\n";
  const nlohmann::json& curves = left.metrics["seams"]["curves"];
  for (size_t c = 0; c < curves.size(); ++c) {
    const nlohmann::json& a = curves[c];
    md << "| " << a["name"].get<std::string>() << " | " << a["kind"].get<std::string>() << " | " << a["vertices"]
       << " | " << a["shared_vertices"] << " | " << figureText(a["gap_cm"]["mean"]) << " | " << figureText(a["gap_cm"]["max"])
       << " | " << figureText(a["normal_jump_deg"], 2);
    if (right) md << " | " << figureText(right->metrics["seams"]["curves"][c]["normal_jump_deg"], 2);
    md << " | " << figureText(a["near_seam_error_cm"]);
    if (right) md << " | " << figureText(right->metrics["seams"]["curves"][c]["near_seam_error_cm"]);
    md << " |\n";
  }
  // Error maps, both layouts, on one scale.
  double high = 1e-3;
  for (const stitch::Evaluation* e : {&left, right})
    if (e) high = std::max(high, e->vertexErrorQuantileCm(0.95));
  std::vector<core::RgbImage> maps;
  for (const stitch::Evaluation* e : {&left, right})
    if (e) {
      std::ostringstream title;
      title << std::fixed << std::setprecision(3) << e->metrics["stitch"].get<std::string>() << ": "
            << e->metrics["vertex_error_cm"].get<double>() << " cm mean, scale 0 to " << std::setprecision(2) << high
            << " cm";
      maps.push_back(renderPatternValues(inputs.garment, e->vertexErrorCm, high, title.str(), 320));
    }
  core::writePng(folder / "error_maps_by_mode.png", contactSheet(maps, 1));
  md << "\n## Per-vertex error (front and back patterns)\n\n![](error_maps_by_mode.png)\n";
  if (!inputs.examples.empty()) {
    std::vector<core::RgbImage> pictures;
    for (const SeamExample& example : inputs.examples)
      pictures.push_back(renderWorstSeams(inputs.garment, example, high));
    core::writePng(folder / "worst_seams.png", contactSheet(pictures, 1));
    md << "\n## Examples, the three curves of largest normal jump marked\n\nColour: per-vertex error, 0 to "
       << std::fixed << std::setprecision(2) << high << " cm.\n\n![](worst_seams.png)\n";
  }
  core::writeTextAtomically(folder / "report.md", md.str());
}

}  // namespace pixelcloth::viz
