#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/garment/garment.h"

namespace pixelcloth::cage {

/// What a cage curve is, as garment.h defines it for the garment's cage lines (seam, loop, centre line, opening,
/// split), with its names.
using garment::CurveKind;
using garment::curveKindFromName;
using garment::curveKindName;

/// One cage curve: an ordered chain of mesh vertices along mesh edges.
struct CageCurve {
  std::string name;  ///< e.g. "side_left", "chest_front", "centre_front", "hem"
  CurveKind kind = CurveKind::Seam;
  bool closed = false;        ///< a closed curve continues from the last vertex back to the first
  std::vector<int> vertices;  ///< mesh vertex indices; consecutive ones (and last-first when closed) share an edge
};

/// A junction of the cage: a mesh vertex where curves meet or where an open curve ends.
struct CageNode {
  std::string name;  ///< stable name, e.g. "armpit_left", "neck_side_left", or "<curve>:<end>" when unnamed
  int vertex = -1;   ///< mesh vertex index
};

/// The cage of a mesh (garment or body): its curves and their junctions.
struct Cage {
  std::vector<CageNode> nodes;
  std::vector<CageCurve> curves;

  /// Curve by name, or nullptr.
  const CageCurve* findCurve(const std::string& name) const;
  /// Node index by name, or -1.
  int findNode(const std::string& name) const;
  /// Every mesh edge of every curve, as (min, max) vertex pairs.
  std::vector<std::pair<int, int>> edges() const;
  /// Throws InputError (prefixed with `context`) when a curve has fewer than 2 vertices, repeats a vertex, uses a
  /// vertex out of range, or has consecutive vertices that share no edge of `F`; or when a node's vertex is not on
  /// any curve.
  void validate(const Eigen::MatrixX3i& F, int numVertices, const std::string& context = "cage") const;
};

/// Nodes derived from curves: every endpoint of an open curve and every vertex shared by two or more curves,
/// named by every curve through it, sorted and joined by '/' ("armhole_back_left/armhole_front_left/side_left/
/// underarm_left"), or "<curve>:<vertex>" for the end of a curve that meets no other. A garment cage and a body cage
/// built with the same curve names therefore give matching node names.
std::vector<CageNode> junctions(const std::vector<CageCurve>& curves);

/// {"nodes": [{"name", "vertex"}], "curves": [{"name", "kind", "closed", "vertices"}]}
nlohmann::json toJson(const Cage& cage);
Cage cageFromJson(const nlohmann::json& json, const std::string& context);

}  // namespace pixelcloth::cage
