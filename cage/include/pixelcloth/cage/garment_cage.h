#pragma once

#include <utility>
#include <vector>

#include "pixelcloth/cage/cage.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::cage {

/// The cage of a garment template (paper section 3; DESIGN.md, "Cage"), every curve a chain of garment vertices along
/// mesh edges:
///  - every seam, kind Seam, named as in `Garment::seams` (stitched: side_left, underarm_left, shoulder_left,
///    sleeve_top_left, ... ; sewn inside a layout: armhole_front_left, armhole_back_left, ...), open;
///  - every opening, kind Opening, closed (T-shirt: hem, neckline, sleeve_hem_left, sleeve_hem_right; necktie:
///    outline);
///  - every cage line of `Garment::lines` with its kind and closedness (chest, waist, bicep_left, bicep_right: closed
///    Loops through both layouts; centre_front, centre_back: CentreLine; side_panel_*, tie_band_*: Split).
/// Nodes are `junctions(curves)`. The result is validated against the garment mesh (throws InputError if a curve
/// leaves the mesh edges).
Cage garmentCage(const garment::Garment& garment);

/// The mesh edges the patches are cut along: every edge of every curve (`cage.edges()`), for
/// `patches::segmentPatches`.
std::vector<std::pair<int, int>> cutEdges(const Cage& cage);

}  // namespace pixelcloth::cage
