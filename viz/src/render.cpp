#include "pixelcloth/viz/render.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/viz/draw.h"

namespace pixelcloth::viz {

using namespace core;

namespace {
Eigen::Matrix3d cameraRotation(const View& view) {
  double az = view.azimuthDegrees * M_PI / 180.0, el = view.elevationDegrees * M_PI / 180.0;
  // Turn the world by -azimuth about y, then tilt by +elevation about x.
  return (Eigen::AngleAxisd(el, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(-az, Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}
}  // namespace

Eigen::Vector2d Projection::toPixel(const Eigen::Vector3d& world) const {
  Eigen::Vector3d c = rotation * (world - centre);
  return {0.5 * width + c.x() * pixelsPerMetre, 0.5 * height - c.y() * pixelsPerMetre};
}

Projection Projection::fit(const View& view, const Eigen::AlignedBox3d& bounds) {
  Projection p;
  p.rotation = cameraRotation(view);
  p.width = view.width;
  p.height = view.height;
  p.centre = bounds.center();
  // Extent of the box's corners on screen.
  double maxX = 1e-9, maxY = 1e-9;
  for (int i = 0; i < 8; ++i) {
    Eigen::Vector3d c = p.rotation * (bounds.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)) - p.centre);
    maxX = std::max(maxX, std::abs(c.x()));
    maxY = std::max(maxY, std::abs(c.y()));
  }
  double usable = 1.0 - 2.0 * view.margin;
  p.pixelsPerMetre = std::min(0.5 * usable * view.width / maxX, 0.5 * usable * view.height / maxY);
  return p;
}

RgbImage renderMeshes(const std::vector<RenderMesh>& meshes, const View& view, Projection* projectionOut) {
  PIXELCLOTH_CHECK(view.width > 0 && view.height > 0, "render: image size must be positive");
  Eigen::AlignedBox3d bounds = view.bounds;
  if (bounds.isEmpty()) {
    for (const RenderMesh& m : meshes)
      for (int i = 0; i < m.V.rows(); ++i) bounds.extend(m.V.row(i).transpose().eval());
  }
  if (bounds.isEmpty()) bounds.extend(Eigen::Vector3d::Zero());
  Projection projection = Projection::fit(view, bounds);
  if (projectionOut) *projectionOut = projection;

  const int ss = 2;  // supersampling factor
  const int w = view.width * ss, h = view.height * ss;
  std::vector<float> depth(static_cast<size_t>(w) * h, -std::numeric_limits<float>::infinity());
  std::vector<Eigen::Vector3f> color(static_cast<size_t>(w) * h, view.background.cast<float>());
  const Eigen::Vector3d light = Eigen::Vector3d(-0.35, 0.45, 1.0).normalized();

  for (const RenderMesh& m : meshes) {
    if (m.F.rows() == 0) continue;
    Eigen::MatrixX3d normals = vertexNormals(m.V, m.F);
    Eigen::MatrixX3d cam(m.V.rows(), 3);
    for (int i = 0; i < m.V.rows(); ++i) {
      Eigen::Vector3d c = projection.rotation * (m.V.row(i).transpose() - projection.centre);
      cam.row(i) << (0.5 * view.width + c.x() * projection.pixelsPerMetre) * ss,
          (0.5 * view.height - c.y() * projection.pixelsPerMetre) * ss, c.z();
    }
    for (int f = 0; f < m.F.rows(); ++f) {
      Eigen::Vector3d p[3] = {cam.row(m.F(f, 0)), cam.row(m.F(f, 1)), cam.row(m.F(f, 2))};
      double area = (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[1].y() - p[0].y()) * (p[2].x() - p[0].x());
      if (std::abs(area) < 1e-12) continue;
      int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
      int x1 = std::min(w - 1, static_cast<int>(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
      int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
      int y1 = std::min(h - 1, static_cast<int>(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          double px = x + 0.5, py = y + 0.5;
          double b0 = ((p[1].x() - px) * (p[2].y() - py) - (p[1].y() - py) * (p[2].x() - px)) / area;
          double b1 = ((p[2].x() - px) * (p[0].y() - py) - (p[2].y() - py) * (p[0].x() - px)) / area;
          double b2 = 1.0 - b0 - b1;
          if (b0 < 0 || b1 < 0 || b2 < 0) continue;
          float z = static_cast<float>(b0 * p[0].z() + b1 * p[1].z() + b2 * p[2].z());
          size_t idx = static_cast<size_t>(y) * w + x;
          if (z <= depth[idx]) continue;
          depth[idx] = z;
          Eigen::Vector3d n = b0 * normals.row(m.F(f, 0)) + b1 * normals.row(m.F(f, 1)) + b2 * normals.row(m.F(f, 2));
          n = projection.rotation * n.normalized();
          Eigen::Vector3d base = m.color;
          if (m.vertexColors.rows() == m.V.rows()) {
            base = b0 * m.vertexColors.row(m.F(f, 0)) + b1 * m.vertexColors.row(m.F(f, 1)) +
                   b2 * m.vertexColors.row(m.F(f, 2));
          } else if (m.faceColors.rows() == m.F.rows()) {
            base = m.faceColors.row(f);
          }
          double diffuse = std::abs(n.dot(light));
          double rim = 0.12 * std::pow(1.0 - std::abs(n.z()), 2.0);
          color[idx] = (base * (0.28 + 0.72 * diffuse) + Eigen::Vector3d::Constant(rim)).cwiseMin(1.0).cast<float>();
        }
      }
    }
  }

  RgbImage image(view.width, view.height);
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      for (int dy = 0; dy < ss; ++dy)
        for (int dx = 0; dx < ss; ++dx) sum += color[static_cast<size_t>(y * ss + dy) * w + (x * ss + dx)];
      sum /= ss * ss;
      image.set(x, y,
                {static_cast<std::uint8_t>(std::lround(255 * std::clamp(sum.x(), 0.f, 1.f))),
                 static_cast<std::uint8_t>(std::lround(255 * std::clamp(sum.y(), 0.f, 1.f))),
                 static_cast<std::uint8_t>(std::lround(255 * std::clamp(sum.z(), 0.f, 1.f)))});
    }
  }
  return image;
}

Eigen::Vector3d colorRamp(double t, bool diverging) {
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  if (diverging) {
    Eigen::Vector3d blue(0.23, 0.30, 0.75), white(0.95, 0.95, 0.95), red(0.71, 0.02, 0.15);
    return t < 0.5 ? Eigen::Vector3d(blue + (white - blue) * (2 * t))
                   : Eigen::Vector3d(white + (red - white) * (2 * t - 1));
  }
  // A perceptual-ish ramp: dark blue, teal, green, yellow.
  static const Eigen::Vector3d stops[4] = {
      {0.27, 0.00, 0.33}, {0.13, 0.57, 0.55}, {0.37, 0.79, 0.38}, {0.99, 0.91, 0.14}};
  double s = t * 3.0;
  int i = std::min(2, static_cast<int>(s));
  return stops[i] + (stops[i + 1] - stops[i]) * (s - i);
}

}  // namespace pixelcloth::viz
