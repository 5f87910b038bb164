// The appendix's basis figures: boundary data on a square patch, filled isotropically and anisotropically.
#include "pixelcloth/viz/basis_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

using namespace patches;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Top view of the heights over the square: pixel (x, y) shows pattern point (u, v) with v up. Colour ramp over
/// [-amplitude, amplitude] (diverging: blue below, white at 0, red above), contour lines every amplitude / 5.
core::RgbImage heightMapImage(const PatchMesh& patch, const Eigen::VectorXd& height, double side, double amplitude,
                              int size) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> value(static_cast<size_t>(size) * size, nan);
  const double scale = size / side;
  for (int f = 0; f < patch.F.rows(); ++f) {
    Eigen::Vector2d p[3];
    double h[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = Eigen::Vector2d(patch.uv(patch.F(f, k), 0) * scale, (side - patch.uv(patch.F(f, k), 1)) * scale);
      h[k] = height(patch.F(f, k));
    }
    const double det = (p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x();
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int x1 = std::min(size - 1, static_cast<int>(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int y1 = std::min(size - 1, static_cast<int>(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d q(x + 0.5, y + 0.5);
        auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
          return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
        };
        const double b0 = cross(p[1], p[2], q) / det, b1 = cross(p[2], p[0], q) / det, b2 = 1.0 - b0 - b1;
        if (b0 < -1e-9 || b1 < -1e-9 || b2 < -1e-9) continue;
        value[static_cast<size_t>(y) * size + x] = b0 * h[0] + b1 * h[1] + b2 * h[2];
      }
  }
  core::RgbImage image(size, size);
  const double step = amplitude / 5.0;
  // A contour between two pixels in different bands; none between two values at zero up to round-off (the nodal
  // lines of antisymmetric data would otherwise be drawn from noise).
  auto crosses = [&](int x, int y, int xn, int yn) {
    const double a = value[static_cast<size_t>(y) * size + x], b = value[static_cast<size_t>(yn) * size + xn];
    if (std::isnan(b) || (std::abs(a) < 1e-6 * step && std::abs(b) < 1e-6 * step)) return false;
    return std::floor(a / step) != std::floor(b / step);
  };
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double v = value[static_cast<size_t>(y) * size + x];
      if (std::isnan(v)) continue;
      Eigen::Vector3d c = viz::colorRamp(std::clamp(0.5 + 0.5 * v / amplitude, 0.0, 1.0), true);
      const bool contour = (x + 1 < size && crosses(x, y, x + 1, y)) || (y + 1 < size && crosses(x, y, x, y + 1));
      if (contour) c *= 0.45;
      image.set(x, y, toColor(c));
    }
  return image;
}

/// Shaded 3D view of the surface (u, height, -v) seen from the front-right and above, shared framing.
core::RgbImage shadedImage(const PatchMesh& patch, const Eigen::VectorXd& height, double side, double amplitude,
                           int size) {
  viz::RenderMesh mesh;
  mesh.V.resize(patch.uv.rows(), 3);
  mesh.vertexColors.resize(patch.uv.rows(), 3);
  for (int v = 0; v < patch.uv.rows(); ++v) {
    mesh.V.row(v) << patch.uv(v, 0) - 0.5 * side, height(v), 0.5 * side - patch.uv(v, 1);
    mesh.vertexColors.row(v) = viz::colorRamp(std::clamp(0.5 + 0.5 * height(v) / amplitude, 0.0, 1.0), true);
  }
  mesh.F = patch.F;
  viz::View view;
  view.azimuthDegrees = 25;
  view.elevationDegrees = 35;
  view.width = view.height = size;
  view.margin = 0.04;
  view.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(-0.5 * side, -amplitude, -0.5 * side),
                                    Eigen::Vector3d(0.5 * side, amplitude, 0.5 * side));
  return viz::renderMeshes({mesh}, view);
}

}  // namespace

namespace {
const core::EnumNames<BoundaryShape, 4> kShapes{"boundary shape",
                                                {{{BoundaryShape::OneBump, "one_bump"},
                                                  {BoundaryShape::TwoBumps, "two_bumps"},
                                                  {BoundaryShape::SineWave, "sine"},
                                                  {BoundaryShape::SCurve, "s_curve"}}}};
}  // namespace

std::vector<BoundaryShape> allBoundaryShapes() { return kShapes.values(); }

std::string boundaryShapeName(BoundaryShape shape) { return kShapes.name(shape); }

Eigen::VectorXd boundaryHeights(const PatchMesh& patch, BoundaryShape shape, double side, double amplitude) {
  PIXELCLOTH_CHECK(side > 0 && std::isfinite(amplitude),
                   "boundary heights: side must be positive and the "
                   "amplitude finite, got "
                       << side << ", " << amplitude);
  Eigen::VectorXd h(patch.boundary.size());
  const double sigma = side / 10.0, eps = 1e-9 * side;
  auto bump = [&](double x) { return amplitude * std::exp(-0.5 * std::pow((x - 0.5 * side) / sigma, 2)); };
  for (size_t j = 0; j < patch.boundary.size(); ++j) {
    const double u = patch.uv(patch.boundary[j], 0), v = patch.uv(patch.boundary[j], 1);
    // Arc length along the counter-clockwise loop from (0, 0).
    double s;
    if (v < eps)
      s = u;
    else if (u > side - eps)
      s = side + v;
    else if (v > side - eps)
      s = 2 * side + (side - u);
    else
      s = 3 * side + (side - v);
    switch (shape) {
      case BoundaryShape::OneBump:
        h(j) = v < eps ? bump(u) : 0.0;
        break;
      case BoundaryShape::TwoBumps:
        h(j) = (v < eps || v > side - eps) ? bump(u) : 0.0;
        break;
      case BoundaryShape::SineWave:
        h(j) = amplitude * std::sin(2 * kPi * 4 * s / (4 * side));
        break;
      case BoundaryShape::SCurve: {
        const double t = std::clamp(v / side, 0.0, 1.0);
        h(j) = amplitude * (2 * t * t * (3 - 2 * t) - 1);
        break;
      }
    }
  }
  return h;
}

void BasisFigureOptions::validate() const {
  PIXELCLOTH_CHECK(side > 0 && std::isfinite(side), "basis figures: side must be positive, got " << side);
  PIXELCLOTH_CHECK(cells >= 2 && cells <= 400, "basis figures: cells must be in [2, 400], got " << cells);
  PIXELCLOTH_CHECK(amplitude > 0 && std::isfinite(amplitude),
                   "basis figures: amplitude must be positive, got " << amplitude);
  PIXELCLOTH_CHECK(pictureSize >= 32 && pictureSize <= 4096,
                   "basis figures: picture size must be in [32, 4096] pixels, got " << pictureSize);
  BasisOptions basis;
  basis.anisotropic = true;
  basis.theta = theta;
  basis.ratio = ratio;
  basis.validate();
}

std::string BasisFigure::name() const { return boundaryShapeName(shape) + (anisotropic ? "_aniso" : "_iso"); }

std::vector<BasisFigure> basisFigures(const BasisFigureOptions& options) {
  options.validate();
  const PatchMesh square = rectanglePatch(options.side, options.side, options.cells, options.cells);
  BasisOptions iso, aniso;
  aniso.anisotropic = true;
  aniso.theta = options.theta;
  aniso.ratio = options.ratio;
  const PatchBasis isoBasis(square, iso), anisoBasis(square, aniso);
  std::vector<BasisFigure> figures;
  for (BoundaryShape shape : allBoundaryShapes()) {
    Eigen::MatrixX3d data = Eigen::MatrixX3d::Zero(square.boundary.size(), 3);
    data.col(2) = boundaryHeights(square, shape, options.side, options.amplitude);
    for (const PatchBasis* basis : {&isoBasis, &anisoBasis}) {
      BasisFigure figure;
      figure.shape = shape;
      figure.anisotropic = basis == &anisoBasis;
      figure.patch = square;
      figure.height = basis->fillAll(data).col(2);
      figure.heightMap = heightMapImage(square, figure.height, options.side, options.amplitude, options.pictureSize);
      figure.shaded = shadedImage(square, figure.height, options.side, options.amplitude, options.pictureSize);
      figures.push_back(std::move(figure));
    }
  }
  return figures;
}

core::RgbImage basisContactSheet(const std::vector<BasisFigure>& figures) {
  std::vector<core::RgbImage> pictures;
  for (const BasisFigure& figure : figures) {
    pictures.push_back(figure.heightMap);
    pictures.push_back(figure.shaded);
  }
  return viz::contactSheet(pictures, 4);
}

std::vector<BasisFigure> writeBasisFigures(const std::filesystem::path& folder, const BasisFigureOptions& options) {
  std::vector<BasisFigure> figures = basisFigures(options);
  for (const BasisFigure& figure : figures) {
    core::writePng(folder / (figure.name() + ".png"), figure.heightMap);
    core::writePng(folder / (figure.name() + "_3d.png"), figure.shaded);
    core::Mesh mesh;
    mesh.V.resize(figure.patch.uv.rows(), 3);
    mesh.V << figure.patch.uv, figure.height;
    mesh.F = figure.patch.F;
    mesh.UV = figure.patch.uv;
    mesh.FUV = figure.patch.F;
    core::writeMesh(folder / (figure.name() + ".obj"), mesh);
  }
  core::writePng(folder / "bases.png", basisContactSheet(figures));
  return figures;
}

}  // namespace pixelcloth::viz
