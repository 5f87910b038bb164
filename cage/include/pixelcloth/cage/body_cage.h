#pragma once

#include "pixelcloth/body/body.h"
#include "pixelcloth/cage/cage.h"
#include "pixelcloth/core/image.h"

namespace pixelcloth::cage {

/// Heights and positions of the body cage, relative to the skeleton (metres).
struct BodyCageOptions {
  double chestBelowSpine1 = 0.0;    ///< chest loop height below the spine1 joint
  double hemBelowRoot = 0.11;       ///< hem (hip) loop height below the root joint
  double armholeOutsideArm = 0.01;  ///< armhole plane distance outside the shoulder (l_arm / r_arm) joint along the arm
  double bicepFromShoulder = 0.135;      ///< bicep loop distance from the shoulder joint along the arm
  double sleeveHemFromShoulder = 0.235;  ///< sleeve-hem loop distance from the shoulder joint along the arm
  double planeTolerance = 0.01;          ///< how closely curves follow their guiding planes (Dijkstra penalty scale)
  void validate() const;
};

/// The cage on a body in its rest T-pose (DESIGN.md "Cage"; paper section 3): the T-shirt cage's curves where the
/// shirt meets the body, with the same names, so junction nodes match the garment cage's by name:
/// loops `neckline`, `chest`, `waist`, `hem`, `bicep_left/right`, `sleeve_hem_left/right`; lines `centre_front`,
/// `centre_back`, `side_left/right` (armpit to hem), `shoulder_left/right` (neck to shoulder point),
/// `sleeve_top_left/right`, `underarm_left/right`, and the armhole loops split at the shoulder point and the armpit
/// into `armhole_front_left/right` and `armhole_back_left/right`. Landmarks are placed from the skeleton (loop
/// heights from spine joints, arm loops along the arm joints) on the surface; each curve is a shortest path along
/// mesh edges through its landmarks, penalised for leaving the curve's guiding plane. Curves that meet share the
/// landmark vertex where they meet; nodes are those shared landmarks, named like `junctions()`. Works for the built-in
/// mannequin and for imported bodies (T-pose, arms along x). Throws InputError when a landmark cannot be found.
Cage bodyCage(const body::Body& body, const BodyCageOptions& options = {});

}  // namespace pixelcloth::cage
