// The demo's static-equilibrium section (eval::runEquilibriumDemo) drawn: the T-shirt's first poses solved by the
// Newton solver to a net force below 1% of a vertex's weight on every vertex, beside projective dynamics' samples of
// the same poses, which stop after a fixed schedule (docs/simulation.md).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "pixelcloth/viz/demo.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

void demoEquilibrium(Report& report, const body::Body& body, const eval::EquilibriumDemo& made) {
  const data::Dataset projective = data::openDataset(made.projective);
  const data::Dataset newton = data::openDataset(made.newton.folder);
  const sim::ShapeComparison& c = made.comparison;
  const data::DatasetStats& ns = newton.info.stats;
  const data::DatasetStats& ps = projective.info.stats;

  // The three pairs that differ most, projective dynamics' shirt beside the equilibrium coloured by the distance.
  std::vector<int> order(c.rows.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return c.mean[a] > c.mean[b]; });
  order.resize(std::min<size_t>(order.size(), 3));
  const garment::Garment garment = data::datasetGarment(newton.info);
  double scale = 0.01;  // the colour scale: the largest vertex distance shown, at least 1 cm
  for (const int k : order) scale = std::max(scale, c.max[k]);
  std::vector<core::RgbImage> pictures;
  nlohmann::json shown = nlohmann::json::array();
  for (const int k : order) {
    const auto [rowA, rowB] = c.rows[k];
    body::Body posed = body;
    posed.mesh = body.posedMesh(body::Pose::fromLeading(newton.pose(rowB)));
    garment::Garment pd = garment, eq = garment;
    pd.mesh.V = projective.positionsOf(rowA).cast<double>();
    eq.mesh.V = newton.positionsOf(rowB).cast<double>();
    const Eigen::VectorXd distance = sim::distancesThroughPattern(pd, pd.mesh.V, eq, eq.mesh.V);
    Eigen::MatrixX3d colors(distance.size(), 3);
    for (int v = 0; v < distance.size(); ++v)
      colors.row(v) = colorRamp(std::isfinite(distance(v)) ? std::clamp(distance(v) / scale, 0.0, 1.0) : 0.0)
                          .transpose();
    core::RgbImage left = renderGarmentOnBody(pd, &posed, 240);
    core::RgbImage right = renderGarmentOnBody(eq, &posed, 240, &colors);
    std::ostringstream label;
    label << std::fixed << std::setprecision(1) << "equilibrium: " << 100 * c.mean[k] << " cm from it";
    drawText(left, {8, 8}, "projective dynamics, sample " + std::to_string(rowA), {0, 0, 0}, 2);
    drawText(right, {8, 8}, label.str(), {0, 0, 0}, 2);
    pictures.push_back(left);
    pictures.push_back(right);
    shown.push_back({{"projective_row", rowA}, {"newton_row", rowB}, {"mean_cm", 100 * c.mean[k]},
                     {"max_cm", 100 * c.max[k]}});
  }
  const std::string picture = "dataset_tshirt_newton/against_projective.png";
  if (!pictures.empty()) writePng(report.folder() / picture, contactSheet(pictures, 2));

  nlohmann::json& figures = report.json()["equilibrium"];
  figures = {{"samples", newton.rows()},
             {"seconds", made.newton.seconds},
             {"check", made.newton.check.summary()},
             {"stats", ns.toJson()},
             {"projective_stats", ps.toJson()},
             {"pairs", c.rows.size()},
             {"mean_distance_cm", 100 * c.meanDistance()},
             {"max_distance_cm", 100 * c.maxDistance()},
             {"colour_scale_cm", 100 * scale},
             {"shown", shown}};
  // The simulation's rejections; the sampler's pruned draws (an arm inside the torso) were never simulated.
  const std::string pruned = data::rejectionName(data::Rejection::ArmInsideTorso);
  const int simulated = ns.simulated();
  std::ostringstream rejections;
  for (const auto& [reason, count] : ns.rejected)
    if (reason != pruned && count > 0) rejections << (rejections.tellp() > 0 ? ", " : "") << count << " " << reason;
  std::ostringstream text;
  text << std::fixed << std::setprecision(2) << "The first " << newton.rows()
       << " poses of the T-shirt dataset simulated again by the Newton solver, run until the net force on every vertex "
          "is below 1% of its weight (`pixelcloth generate --solver newton`, docs/simulation.md): "
       << ns.accepted << " kept of " << simulated << " simulated";
  if (rejections.tellp() > 0) text << " (" << rejections.str() << ")";
  text << ", " << std::setprecision(0) << (ns.accepted > 0 ? ns.sumIterations / ns.accepted : 0.0)
       << std::setprecision(2) << " Newton iterations and "
       << (ns.accepted > 0 ? ns.sumSeconds / ns.accepted : 0.0)
       << " s a kept pose on one core, the largest net force left on a kept sample " << 100 * ns.maxResidualForceRatio
       << "% of its vertex's weight; " << made.newton.check.summary()
       << ". Projective dynamics takes " << (ps.accepted > 0 ? ps.sumSeconds / ps.accepted : 0.0)
       << " s a pose and stops after its fixed schedule (the same cloth, stretch, bending and weight; its contact "
          "springs hold friction, the Newton path is frictionless): on the "
       << c.rows.size()
       << " poses both kept, its shirts lie on average " << 100 * c.meanDistance()
       << " cm from the equilibria (the farthest vertex " << 100 * c.maxDistance()
       << " cm). Pictures: the poses where they differ most, projective dynamics' shirt beside the equilibrium, each "
          "vertex coloured by its distance from projective dynamics' (dark blue 0, yellow "
       << 100 * scale << " cm). In the 3D viewer: dataset_tshirt_newton.";
  report.section("Static equilibrium", text.str(),
                 pictures.empty() ? std::vector<std::string>{} : std::vector<std::string>{picture});
}

}  // namespace pixelcloth::viz
