#include "pixelcloth/viz/motion_pictures.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/line_chart.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

View frameStripView() {
  View view;
  view.width = 240;
  view.height = 320;
  view.azimuthDegrees = 20;
  view.elevationDegrees = 10;
  return view;
}

core::RgbImage renderFrameStrip(int frames, int count, double fps, const std::function<core::RgbImage(int)>& render) {
  PIXELCLOTH_CHECK(frames >= 1 && count >= 1 && fps > 0,
                   "frame strip: " << count << " of " << frames << " frames at " << fps << " fps");
  const int n = std::min(count, frames);
  std::vector<core::RgbImage> pictures;
  for (int k = 0; k < n; ++k) {
    const int f = n == 1 ? 0 : static_cast<int>(std::lround(k * (frames - 1.0) / (n - 1)));
    core::RgbImage picture = render(f);
    std::ostringstream label;
    label << "frame " << f << ", " << std::fixed << std::setprecision(2) << f / fps << " s";
    drawText(picture, {8, 8}, label.str(), core::Color{40, 40, 40}, 1);
    pictures.push_back(std::move(picture));
  }
  return contactSheet(pictures, n);
}

core::RgbImage renderGarmentStrip(const Eigen::MatrixX3i& bodyFaces, const std::vector<Eigen::MatrixX3d>& body,
                                  const core::Mesh& garment, const std::vector<Eigen::MatrixX3d>& garmentFrames,
                                  double fps, int count) {
  PIXELCLOTH_CHECK(!body.empty() && body.size() == garmentFrames.size() && count >= 1,
                   "garment strip: " << body.size() << " body frames, " << garmentFrames.size() << " garment frames");
  View view = frameStripView();
  for (const Eigen::MatrixX3d& frame : body)
    for (Eigen::Index i = 0; i < frame.rows(); i += 7) view.bounds.extend(frame.row(i).transpose().eval());
  return renderFrameStrip(static_cast<int>(body.size()), count, fps, [&](int f) {
    const RenderMesh skin{body[f], bodyFaces, {}, {}, {0.87, 0.76, 0.66}};
    const RenderMesh cloth{garmentFrames[f], garment.F, {}, {}, {0.25, 0.45, 0.75}};
    return renderMeshes({skin, cloth}, view);
  });
}

core::RgbImage renderTemporalMetrics(const motion::TemporalMetrics& metrics) {
  const int frames = static_cast<int>(metrics.insideVertices.size());
  PIXELCLOTH_CHECK(frames > 0, "temporal metrics: no frames");
  ChartSeries garment{"garment", {}, {}}, body{"body", {}, {}}, inside{"garment vertices inside the body", {}, {}};
  for (int f = 0; f < frames; ++f) {
    const double t = f / metrics.fps;
    if (std::isfinite(metrics.garmentJitterCm[f])) {
      garment.x.push_back(t);
      garment.y.push_back(metrics.garmentJitterCm[f]);
      body.x.push_back(t);
      body.y.push_back(metrics.bodyJitterCm[f]);
    }
    inside.x.push_back(t);
    inside.y.push_back(metrics.insideVertices[f]);
  }
  std::vector<core::RgbImage> charts;
  if (!garment.x.empty()) {
    LineChart jitter{"jitter |x(t+1) - 2x(t) + x(t-1)|", "time, s", "cm, mean over vertices", {garment, body}};
    charts.push_back(renderLineChart(jitter, 640, 320));
  }
  LineChart depth{"garment inside the body", "time, s", "vertices", {inside}};
  charts.push_back(renderLineChart(depth, 640, 320));
  ChartSeries gap{"patch networks apart on the cage curves", {}, {}};
  for (int f = 0; f < static_cast<int>(metrics.seamGapCm.size()); ++f)
    if (std::isfinite(metrics.seamGapCm[f])) {
      gap.x.push_back(f / metrics.fps);
      gap.y.push_back(metrics.seamGapCm[f]);
    }
  if (!gap.x.empty()) {
    LineChart seams{"seam gap before blending", "time, s", "cm, mean over curve vertices", {gap}};
    charts.push_back(renderLineChart(seams, 640, 320));
  }
  return contactSheet(charts, static_cast<int>(charts.size()));
}

std::vector<std::string> writeSequencePictures(const std::filesystem::path& out, const Eigen::MatrixX3i& bodyFaces,
                                               const core::Mesh& garment, const eval::MotionPrediction& sequence) {
  core::writePng(out / "strip.png",
                 renderGarmentStrip(bodyFaces, sequence.body, garment, sequence.garment, sequence.fps));
  core::writePng(out / "temporal.png", renderTemporalMetrics(sequence.metrics));
  return {"strip.png", "temporal.png"};
}

}  // namespace pixelcloth::viz
