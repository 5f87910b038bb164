#pragma once

#include "pixelcloth/body/body.h"

namespace pixelcloth::testing {

/// The default mannequin, built once per test process (meshing takes a few seconds).
inline const body::Body& mannequin() {
  static const body::Body body = body::makeMannequin();
  return body;
}

/// A coarse mannequin (~2K vertices, 2 cm edges): enough for file round trips and embeddings, quick to build.
inline const body::Body& coarseMannequin() {
  static const body::Body body = [] {
    body::MannequinOptions options;
    options.edgeLength = 0.02;
    return body::makeMannequin(options);
  }();
  return body;
}

}  // namespace pixelcloth::testing
