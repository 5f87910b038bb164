// Pictures of the stages' results: posed bodies, cloth-image previews, per-vertex values in pattern space.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/patches/frame.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/motion_pictures.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

using namespace core;
using body::Body;
using body::Pose;
using patches::ClothImage;
using patches::ClothLayer;

void writePosedBodies(const std::filesystem::path& folder, const Body& body, const std::vector<Pose>& poses,
                      const nlohmann::json& info) {
  ensureOutputFolder(folder);
  View view;
  view.width = view.height = 320;
  view.azimuthDegrees = 20;
  view.elevationDegrees = 10;
  // One scale for every pose: the body's rest box widened by the reach of raised and swung arms.
  for (int i = 0; i < body.mesh.numVertices(); ++i) view.bounds.extend(body.mesh.V.row(i).transpose().eval());
  view.bounds.extend(Eigen::Vector3d(view.bounds.center().x(), view.bounds.max().y() + 0.3, 0.6));
  view.bounds.extend(Eigen::Vector3d(view.bounds.center().x(), view.bounds.min().y(), -0.6));
  nlohmann::json list = nlohmann::json::array();
  std::vector<float> vectors;
  std::vector<RgbImage> pictures;
  Progress progress("pose", static_cast<std::int64_t>(poses.size()));
  for (size_t i = 0; i < poses.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "posed_%03zu.obj", i);
    Mesh posed;
    posed.V = body.posedVertices(poses[i]);
    posed.F = body.mesh.F;
    writeMesh(folder / name, posed);
    nlohmann::json entry = poseToJson(poses[i]);
    entry["mesh"] = name;
    list.push_back(entry);
    Eigen::VectorXf v = poses[i].toVector();
    vectors.insert(vectors.end(), v.data(), v.data() + v.size());
    if (pictures.size() < 24) pictures.push_back(renderPosedBody(body, poses[i], view));
    progress.advance();
  }
  progress.finish();
  writeNpy(folder / "poses.npy", vectors, {static_cast<std::int64_t>(poses.size()), body::kPoseSize});
  nlohmann::json json = info;
  json["poses"] = list;
  writeJson(folder / "poses.json", json);
  writePng(folder / "posed.png", contactSheet(pictures, 6));
}

core::RgbImage renderPoseStrip(const Body& body, const std::vector<Pose>& poses, double fps, int count) {
  PIXELCLOTH_CHECK(!poses.empty() && count >= 1, "pose strip: no poses");
  View view = frameStripView();
  for (int i = 0; i < body.mesh.numVertices(); ++i) view.bounds.extend(body.mesh.V.row(i).transpose().eval());
  view.bounds.extend(Eigen::Vector3d(view.bounds.center().x(), view.bounds.max().y() + 0.3, 0.6));
  view.bounds.extend(Eigen::Vector3d(view.bounds.center().x(), view.bounds.min().y(), -0.6));
  return renderFrameStrip(static_cast<int>(poses.size()), count, fps,
                          [&](int frame) { return renderPosedBody(body, poses[frame], view); });
}

core::RgbImage renderClothImage(const ClothImage& image, const PreviewOptions& options) {
  image.validate();
  PIXELCLOTH_CHECK(std::isfinite(options.range) && options.range >= 0,
                   "preview range must be >= 0 metres, got " << options.range);
  PIXELCLOTH_CHECK(options.paddingBrightness >= 0 && options.paddingBrightness <= 1,
                   "preview padding brightness must be in [0, 1], got " << options.paddingBrightness);
  float range[3];
  for (int c = 0; c < 3; ++c) {
    range[c] = options.range;
    if (range[c] > 0) continue;
    float largest = 1e-6f;
    for (const ClothLayer& l : image.layers) {
      const Eigen::MatrixXf& channel = c == 0 ? l.du : c == 1 ? l.dv : l.dn;
      largest = std::max(largest, (l.mask.array() > 0.5f).select(channel.array().abs(), 0.0f).maxCoeff());
    }
    range[c] = largest;
  }
  const int L = static_cast<int>(image.layers.size());
  core::RgbImage rgb(L * image.width, image.height);
  for (int l = 0; l < L; ++l) {
    const ClothLayer& layer = image.layers[l];
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        float m = layer.mask(y, x);
        if (m < 0.5f) continue;  // empty: stays white
        float scale = m < 1.5f ? options.paddingBrightness : 1.0f;
        float v[3] = {layer.du(y, x), layer.dv(y, x), layer.dn(y, x)};
        core::Color color;
        for (int c = 0; c < 3; ++c) {
          float t = std::clamp(0.5f + 0.5f * v[c] / range[c], 0.0f, 1.0f);
          color[c] = static_cast<std::uint8_t>(std::lround(255.0f * t * scale));
        }
        rgb.set(l * image.width + x, y, color);
      }
  }
  return rgb;
}

core::RgbImage renderPatternValues(const garment::Garment& garment, const Eigen::VectorXd& values, double maxValue,
                                   const std::string& title, int size, bool blueToRed) {
  PIXELCLOTH_CHECK(values.size() == garment.mesh.numVertices(),
                   "pattern picture: " << values.size() << " values for " << garment.mesh.numVertices() << " vertices");
  const int titleHeight = 24, gap = 8, layouts = garment.numLayouts();
  core::RgbImage image(layouts * size + (layouts - 1) * gap, size + titleHeight);
  viz::drawText(image, {6, 6}, title, {0, 0, 0}, viz::textExtent(title, 2).x() + 12 <= image.width ? 2 : 1);
  const double scale = maxValue > 0 ? maxValue : 1;
  for (int l = 0; l < layouts; ++l) {
    const patches::ImageFrame frame = patches::layoutFrame(garment, l, size);
    const int x0 = l * (size + gap);
    for (int f = 0; f < garment.mesh.numFaces(); ++f) {
      if (garment.faceLayout[f] != l) continue;
      double mean = 0;
      Eigen::Vector2d corner[3];
      for (int k = 0; k < 3; ++k) {
        mean += values[garment.mesh.F(f, k)] / 3;
        corner[k] =
            frame.toPixel(garment.mesh.UV.row(garment.mesh.FUV(f, k)).transpose()) + Eigen::Vector2d(x0, titleHeight);
      }
      const Eigen::Vector3d c = viz::colorRamp(std::clamp(mean / scale, 0.0, 1.0), blueToRed);
      viz::fillTriangle(image, corner[0], corner[1], corner[2],
                        {static_cast<std::uint8_t>(255 * c.x()), static_cast<std::uint8_t>(255 * c.y()),
                         static_cast<std::uint8_t>(255 * c.z())});
    }
    viz::drawText(image, {x0 + 6, titleHeight + size - 14}, garment.layouts[l], {90, 90, 90}, 1);
  }
  return image;
}

core::RgbImage renderReconstructionErrors(const garment::Garment& garment,
                                          const recon::DatasetReconstructionReport& report) {
  const std::vector<recon::ReconstructionMethod> methods = recon::allReconstructionMethods();
  const int M = static_cast<int>(methods.size());
  PIXELCLOTH_CHECK(static_cast<int>(report.meanVertexError.size()) == M,
                   "error maps: " << report.meanVertexError.size() << " methods' errors, expected " << M);
  // Error maps: every method on one colour scale (the largest mean vertex error of any method, at least 1 cm).
  double scale = 0.01;
  for (const Eigen::VectorXd& e : report.meanVertexError) scale = std::max(scale, e.maxCoeff());
  std::vector<core::RgbImage> maps;
  for (int m = 0; m < M; ++m) {
    std::ostringstream title;
    title << recon::reconstructionMethodName(methods[m]) << " " << std::fixed << std::setprecision(2)
          << 100 * report.meanVertexError[m].mean() << " cm (0-" << std::setprecision(1) << 100 * scale << ")";
    maps.push_back(renderPatternValues(garment, report.meanVertexError[m], scale, title.str()));
  }
  int width = 0, height = 0;
  for (const auto& map : maps) {
    width = std::max(width, map.width);
    height += map.height + 8;
  }
  core::RgbImage sheet(width, height);
  int y = 0;
  for (const auto& map : maps) {
    viz::paste(sheet, map, 0, y);
    y += map.height + 8;
  }
  return sheet;
}

}  // namespace pixelcloth::viz
