#pragma once

#include <string>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

/// Pictures for people: contact sheets of bodies and garments, built on renderMeshes.

/// The body sheet: front view with the skeleton drawn over it, skin weights (each joint a colour,
/// blended by weight), the three collision parts (overlaps in a mixed colour), and a side view.
/// Each panel `panelSize` pixels square.
core::RgbImage renderBodySheet(const body::Body& body, int panelSize = 480);

/// One shaded view of a posed body (and optionally a garment on it), with its skeleton.
core::RgbImage renderPosedBody(const body::Body& body, const body::Pose& pose, const View& view,
                               bool drawSkeleton = true);

/// Pictures laid out in a grid of `columns`, white gaps of `gap` pixels.
core::RgbImage contactSheet(const std::vector<core::RgbImage>& pictures, int columns, int gap = 8);

/// The garment's 3D placement over the body (front, three-quarter and back views), its panels coloured, or each vertex
/// by `vertexColors` (#V x 3 in [0, 1]) when given.
core::RgbImage renderGarmentOnBody(const garment::Garment& garment, const body::Body* body, int panelSize = 480,
                                   const Eigen::MatrixX3d* vertexColors = nullptr);

/// The colour given to joint j in weight pictures (RGB in [0, 1]).
Eigen::Vector3d jointColor(int joint);

}  // namespace pixelcloth::viz
