#pragma once
// Lines added to a finished garment mesh: a mesh edge split in two, and a straight pattern-space line made a chain of
// mesh edges by splitting the triangles it crosses (the body loops and patch splits placed on an imported garment).

#include <vector>

#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

/// Splits the mesh edge (a, b) at a + t (b - a): a new vertex whose rest position, and UV in every layout whose faces
/// hold the edge, are interpolated; each face on the edge is split in two (same layout and panel, same orientation);
/// the new vertex goes between a and b in every seam, opening and cage line running along the edge. The garment is no
/// longer a template's exact mesh (its recipe is cleared). Returns the new vertex. Throws `InputError` when (a, b) is
/// no mesh edge or t is not strictly between 0 and 1.
int splitEdge(Garment& garment, int a, int b, double t);

/// Makes the straight pattern-space segment from vertex `from` to vertex `to` (both in `layout`) a chain of mesh edges:
/// walking from `from` through the layout's triangles, each edge the segment crosses is split where it crosses it, or,
/// when an end of that edge lies within `snap` times the edge's length of the segment, that vertex is taken instead (so
/// no sliver triangles are made; the chain then bends by at most that much, and walks on straight to `to`). Crossed seams, openings and cage lines get the new
/// vertices. Returns the chain from `from` to `to`, consecutive vertices sharing a mesh edge. Throws `InputError`
/// naming the vertices when the segment leaves the layout (a concave outline) or either end is not in the layout.
std::vector<int> insertPatternLine(Garment& garment, int layout, int from, int to, double snap = 0.2);

/// Flips edges of the garment's triangles towards a constrained Delaunay triangulation of each layout's pattern space
/// (Lawson's flips): an edge inside one layout that runs along no seam, opening or cage line, whose two triangles
/// include one with an angle under `belowDegrees`, is replaced by the other diagonal of their quad when the angles
/// opposite it sum to more than 180 degrees. Vertices do not move, so rest shapes and positions stay; what inserting
/// lines cut thin is made fat again, as far as the curves allow. Returns the number of flips.
int flipThinTriangles(Garment& garment, double belowDegrees = 20);

/// The smallest angle of any triangle of the garment in pattern space, degrees (the template's mesher keeps 20.7).
double smallestPatternAngleDegrees(const Garment& garment);

}  // namespace pixelcloth::garment
