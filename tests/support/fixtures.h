#pragma once

#include <Eigen/Core>
#include <cmath>

#include "pixelcloth/garment/garment.h"
#include "support/body_fixtures.h"

namespace pixelcloth::testing {

/// The default T-shirt, built once per test process.
inline const garment::Garment& tshirt() {
  static const garment::Garment garment = garment::makeTShirt();
  return garment;
}

/// A smooth field over the garment's rest positions (the same for both UVs of a seam vertex): #V x 3,
/// centimetres-sized.
inline Eigen::MatrixXf smoothOffsets(const garment::Garment& g) {
  Eigen::MatrixXf x(g.mesh.numVertices(), 3);
  for (int v = 0; v < g.mesh.numVertices(); ++v) {
    const Eigen::Vector3d p = g.mesh.V.row(v);
    x.row(v) << 0.02 * std::sin(6 * p.x()), 0.01 * std::cos(5 * p.y()), 0.015 * std::sin(4 * p.x() + 3 * p.y());
  }
  return x;
}

}  // namespace pixelcloth::testing
