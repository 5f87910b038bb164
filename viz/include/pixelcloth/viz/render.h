#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "pixelcloth/core/image.h"

namespace pixelcloth::viz {

/// One mesh to draw. Colours in [0, 1]: per vertex (#V x 3, interpolated), else per face (#F x 3),
/// else `color` everywhere.
struct RenderMesh {
  Eigen::MatrixX3d V;             ///< #V x 3 positions, metres
  Eigen::MatrixX3i F;             ///< #F x 3
  Eigen::MatrixX3d vertexColors;  ///< optional #V x 3
  Eigen::MatrixX3d faceColors;    ///< optional #F x 3
  Eigen::Vector3d color{0.8, 0.8, 0.8};
};

/// An orthographic camera turning around the vertical axis. Azimuth 0 looks at the body's front
/// (from +Z, the wearer's left on the image's right); 90 looks at the wearer's left side.
struct View {
  double azimuthDegrees = 0.0;
  double elevationDegrees = 0.0;  ///< positive looks down from above
  int width = 512;
  int height = 512;
  double margin = 0.06;  ///< fraction of the image kept free around the fitted bounds
  Eigen::Vector3d background{1.0, 1.0, 1.0};
  /// Region to frame; when empty, the bounding box of all meshes drawn.
  Eigen::AlignedBox3d bounds;
};

/// World-to-pixel mapping of a View once fitted: for overlays (skeletons, markers) on a rendering.
struct Projection {
  Eigen::Matrix3d rotation;  ///< world to camera (x right, y up, z towards the viewer)
  Eigen::Vector3d centre;    ///< world point at the image centre
  double pixelsPerMetre = 1;
  int width = 0, height = 0;
  Eigen::Vector2d toPixel(const Eigen::Vector3d& world) const;
  static Projection fit(const View& view, const Eigen::AlignedBox3d& bounds);
};

/// Renders shaded meshes (z-buffer, smooth normals, two-sided diffuse light, 2x2 supersampling).
/// Returns the picture and, through `projection` if given, the mapping it used.
core::RgbImage renderMeshes(const std::vector<RenderMesh>& meshes, const View& view, Projection* projection = nullptr);

/// A colour ramp for values in [0, 1] (blue - white - red when `diverging`, else dark blue - yellow).
Eigen::Vector3d colorRamp(double t, bool diverging = false);

}  // namespace pixelcloth::viz
