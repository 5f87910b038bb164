#pragma once

#include "pixelcloth/garment/garment.h"
#include "support/body_fixtures.h"

namespace pixelcloth::testing {

/// The default T-shirt, built once per test process.
inline const garment::Garment& tshirt() {
  static const garment::Garment garment = garment::makeTShirt();
  return garment;
}

}  // namespace pixelcloth::testing
