#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "pixelcloth/core/image.h"
#include "pixelcloth/patches/basis.h"

namespace pixelcloth::viz {

/// Boundary data of the appendix's basis figures, as heights around a square patch's boundary loop.
enum class BoundaryShape {
  OneBump,   ///< a Gaussian bump at the middle of the bottom edge (sigma = side / 10)
  TwoBumps,  ///< the same bump at the middle of the bottom edge and of the top edge
  SineWave,  ///< four periods of a sine around the whole loop (zero at the corners)
  SCurve,    ///< bottom edge at -amplitude, top edge at +amplitude, both sides climbing along an S (smoothstep)
};

/// All shapes, in the order of the figures' rows.
std::vector<BoundaryShape> allBoundaryShapes();
/// Short file-name stem: "one_bump", "two_bumps", "sine", "s_curve".
std::string boundaryShapeName(BoundaryShape shape);

/// Heights (metres) at the boundary loop of a square patch [0, side]^2 whose loop runs counter-clockwise from (0, 0),
/// e.g. `rectanglePatch(side, side, n, n)`: one value per `patch.boundary` entry, in [-amplitude, amplitude].
Eigen::VectorXd boundaryHeights(const patches::PatchMesh& patch, BoundaryShape shape, double side, double amplitude);

/// Settings of the basis figures.
struct BasisFigureOptions {
  double side = 0.2;                  ///< metres, side of the square patch
  int cells = 40;                     ///< grid cells per side (each split into 4 triangles)
  double amplitude = 0.04;            ///< metres, largest boundary height
  double theta = 0.5235987755982988;  ///< radians, anisotropic direction (30 degrees)
  double ratio = 0.1;                 ///< anisotropic ratio, see BasisOptions::ratio
  int pictureSize = 320;              ///< pixels, side of each picture
  /// Throws `InputError` for non-positive sizes, fewer than 2 cells, too small pictures or invalid anisotropy.
  void validate() const;
};

/// One filled membrane of the figures.
struct BasisFigure {
  BoundaryShape shape = BoundaryShape::OneBump;
  bool anisotropic = false;
  patches::PatchMesh patch;  ///< the square's mesh
  Eigen::VectorXd height;    ///< #n heights per local vertex, metres (boundary data and its fill)
  core::RgbImage heightMap;  ///< top view, colour ramp over [-amplitude, amplitude] with contour lines
  core::RgbImage shaded;     ///< shaded 3D view of the surface (u, v, height)
  std::string name() const;  ///< e.g. "one_bump_aniso"
};

/// The appendix's figures: every boundary shape filled isotropically and anisotropically (shapes in
/// `allBoundaryShapes` order, isotropic first).
std::vector<BasisFigure> basisFigures(const BasisFigureOptions& options = {});

/// The contact sheet: one row per boundary shape; columns: isotropic top view, isotropic 3D view, anisotropic top
/// view, anisotropic 3D view.
core::RgbImage basisContactSheet(const std::vector<BasisFigure>& figures);

/// Writes the figures into `folder`: `<name>.png` (top view), `<name>_3d.png`, `<name>.obj` (vertices
/// (u, v, height) in metres, texture coordinates (u, v)) for each figure, and `bases.png` (the contact sheet).
/// Returns the figures.
std::vector<BasisFigure> writeBasisFigures(const std::filesystem::path& folder, const BasisFigureOptions& options = {});

}  // namespace pixelcloth::viz
