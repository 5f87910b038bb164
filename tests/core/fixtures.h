#pragma once

#include "pixelcloth/core/body.h"
#include "pixelcloth/core/garment.h"

namespace pixelcloth::testing {

/// The default mannequin, built once per test process (meshing takes a few seconds).
inline const core::Body& mannequin() {
  static const core::Body body = core::makeMannequin();
  return body;
}

/// A coarse mannequin (~2K vertices, 2 cm edges): enough for file round trips and embeddings, quick to build.
inline const core::Body& coarseMannequin() {
  static const core::Body body = [] {
    core::MannequinOptions options;
    options.edgeLength = 0.02;
    return core::makeMannequin(options);
  }();
  return body;
}

/// The default T-shirt, built once per test process.
inline const core::Garment& tshirt() {
  static const core::Garment garment = core::makeTShirt();
  return garment;
}

}  // namespace pixelcloth::testing
