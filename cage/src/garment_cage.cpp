// The cage of a garment template: its seams, openings and cage lines as one curve network.
#include "pixelcloth/cage/garment_cage.h"

namespace pixelcloth::cage {

Cage garmentCage(const garment::Garment& garment) {
  Cage cage;
  for (const garment::Seam& seam : garment.seams)
    cage.curves.push_back({seam.name, CurveKind::Seam, false, seam.vertices});
  for (const garment::Opening& opening : garment.openings)
    cage.curves.push_back({opening.name, CurveKind::Opening, true, opening.vertices});
  for (const garment::CageLine& line : garment.lines)
    cage.curves.push_back({line.name, line.kind, line.closed, line.vertices});
  cage.nodes = junctions(cage.curves);
  cage.validate(garment.mesh.F, garment.mesh.numVertices(), garment.name + " cage");
  return cage;
}

std::vector<std::pair<int, int>> cutEdges(const Cage& cage) { return cage.edges(); }

}  // namespace pixelcloth::cage
