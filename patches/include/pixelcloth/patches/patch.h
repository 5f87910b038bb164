#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "pixelcloth/garment/garment.h"

namespace pixelcloth::patches {

/// One patch: a connected region of one layout of a garment, bounded by cage curves (paper section 3).
struct Patch {
  /// 0-based, ordered by layout, then rows top to bottom (the top of the patch's UV box in 5 cm steps), then left to
  /// right (UV box centre).
  int id = 0;
  int layout = 0;             ///< index into Garment::layouts
  std::vector<int> faces;     ///< garment faces
  std::vector<int> vertices;  ///< garment vertices used by the faces, sorted
  std::vector<int> boundary;  ///< garment vertices on the patch's outer boundary, ordered counter-clockwise in UV
  std::vector<int> interior;  ///< the other vertices, sorted
};

/// A patch as its own small mesh in pattern space (the domain of its Poisson bases).
struct PatchMesh {
  Eigen::MatrixX2d uv;            ///< #n x 2 pattern-space coordinates of the patch's vertices, metres
  Eigen::MatrixX3i F;             ///< #f x 3 local triangles, counter-clockwise in UV
  std::vector<int> boundary;      ///< local indices of the ordered boundary loop
  std::vector<int> interior;      ///< local indices of the other vertices
  std::vector<int> globalVertex;  ///< local index -> garment vertex
};

/// Splits every layout of `garment` into patches along `cuts`: faces are connected across a mesh edge unless the
/// edge is one of `cuts` (pairs of garment vertices, any order) or a layout boundary. Each connected set of faces
/// becomes a patch. Throws InputError if a patch's boundary is not one simple loop (e.g. a cut that ends inside).
std::vector<Patch> segmentPatches(const garment::Garment& garment, const std::vector<std::pair<int, int>>& cuts);

/// The garment's patches along its own cage's cuts (cage::garmentCage): the T-shirt's 28, the necktie's.
std::vector<Patch> garmentPatches(const garment::Garment& garment);

/// The patch's own mesh: its faces in the UV space of its layout, with local indices.
PatchMesh patchMesh(const garment::Garment& garment, const Patch& patch);

/// Pixel extent (width, height) of a patch's pattern-space bounding box in its layout's `size` x `size` cloth image
/// (`layoutFrame(garment, patch.layout, size)`): what must fit in 128 px for a 160 px crop with 16 px of context.
Eigen::Vector2d patchPixelExtent(const garment::Garment& garment, const Patch& patch, int size = 512);

}  // namespace pixelcloth::patches
