#pragma once
// An imported garment fitted to a body (`garment --import OBJ --fit-to BODY`): the cage lines a template carries from
// its pattern code (chest, waist and bicep loops, centre lines, side-panel splits; paper section 3) placed where that
// body's cage meets the garment dressed on it, cut into the mesh, and every patch split until it fits its image.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::patches {

struct BodyFitOptions {
  /// Move the garment first so that the centre of its neckline sits where the T-shirt template's sits on this body's
  /// neckline loop (only when the garment has an opening named `neckline`).
  bool alignNeckline = true;
  /// Where the side-panel splits leave the chest line, as a fraction of its pattern length from the centre line to the
  /// side seam (the template's 0.15 m of 0.27 m).
  double sidePanelFraction = 0.55;
  int imageSize = 512;    ///< the patch images' layout size, pixels (patches/frame.h)
  int patchPixels = 128;  ///< every patch's box must fit this many pixels of it, split until it does
  double snap = 0.2;      ///< insertPatternLine's snap: crossings this near a vertex (fraction of the edge) take it
  /// Throws `InputError` naming the field out of range.
  void validate() const;
};

struct BodyFitReport {
  Eigen::Vector3d moved = Eigen::Vector3d::Zero();  ///< translation applied to the garment by the neckline alignment
  std::vector<std::string> lines;                   ///< cage lines added, in order
  std::vector<std::string> skipped;                 ///< lines not placed, each with the reason
  int addedVertices = 0;
  int flippedEdges = 0;  ///< edges flipped to fatten the triangles the cuts made thin (garment::flipThinTriangles)
  double smallestAngleDegrees = 0;  ///< the smallest triangle angle in pattern space at the end
  int patches = 0;
  double largestPatchPixels = 0;  ///< the largest patch box side at the end, pixels of an imageSize image
  /// One line: "moved by (0.00, 0.02, -0.01) m; 10 cage lines (chest, waist, ...), 212 vertices added, 40 edges
  /// flipped, smallest angle 8.8 deg; 28 patches, the largest 124 px".
  std::string summary() const;
};

/// Fits `garment` (one without cage lines: an OBJ imported without a cage file) to `body` in its rest pose:
///  1. aligns its neckline to the body's (BodyFitOptions::alignNeckline);
///  2. dresses it on the body (cage::dressGarment) to see where the body's cage meets the cloth;
///  3. chest and waist loops: the side seams (`side_left`, `side_right`) are cut where the dressed cloth crosses the
///     height of the body's loop, and joined by a straight pattern line across the front and the back layout;
///     bicep loops likewise between the `underarm_*` and `sleeve_top_*` seams at the body's bicep loop;
///  4. centre lines from the neckline to the hem at the body's centre plane, in the front and the back layout;
///  5. side-panel splits from the chest line straight down the pattern to the hem, on both sides of both centre lines;
///  6. any patch whose box is larger than patchPixels of its layout's image is split across its longer side;
///  7. thin triangles the cuts made are fattened by edge flips (garment::flipThinTriangles).
/// Lines are named as the template's (garment.h, CageLine), so dressing morphs them onto their body namesakes; a line
/// whose seams or openings the garment lacks, or whose straight pattern line would leave its layout, is skipped with
/// the reason in the report. Throws `InputError` when the garment already has cage lines, when dressing refuses it,
/// or when a patch too large for its image cannot be split.
BodyFitReport fitGarmentToBody(garment::Garment& garment, const body::Body& body, const BodyFitOptions& options = {});

}  // namespace pixelcloth::patches
