#pragma once

#include "pixelcloth/cage/garment_cage.h"
#include "support/fixtures.h"

namespace pixelcloth::testing {

/// The default T-shirt's cage, built once per test process.
inline const cage::Cage& tshirtCage() {
  static const cage::Cage cage = cage::garmentCage(tshirt());
  return cage;
}

}  // namespace pixelcloth::testing
