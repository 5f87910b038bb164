#pragma once
// A user's garment OBJ (positions and per-corner UVs, as Marvelous Designer, CLO or other cloth programs write them)
// brought in without a cage file, and the exporter that writes our garments the way such programs do.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

/// How the OBJ's positions are brought into our conventions (metres, Y up, body facing +Z, x to the wearer's left):
/// turned to Y up, then scaled, then moved.
struct ObjImportOptions {
  std::string name;  ///< garment name; empty: the OBJ's file stem
  /// The file's up axis, 'y' or 'z'. A Z-up file (its body facing -Y) is turned to Y up, body facing +Z:
  /// (x, y, z) -> (x, z, -y).
  char up = 'y';
  double scale = 1.0;                                   ///< positions multiplied by this (after the turn), > 0
  Eigen::Vector3d translate = Eigen::Vector3d::Zero();  ///< then added, metres
  /// Throws `InputError` naming the field: an up axis other than 'y' or 'z', a scale that is not finite and positive, a
  /// translation that is not finite.
  void validate() const;
};

/// What importGarmentObj fixed on the way in, one note per fix.
struct ObjImportReport {
  /// e.g. "island 3 (left_sleeve): UVs rescaled x41.7 to its 3D area (...)", "island 2 (back): UVs mirrored (they ran
  /// clockwise seen from outside)", "island 4 (left_sleeve): holds vertex 212 twice (a tube): cut in two along 12
  /// edges through its middle", "the faces pointed into the garment: turned round".
  std::vector<std::string> notes;
  /// One line: "no fixes" or "3 fixes: <note>; <note>; ...".
  std::string summary() const;
};

/// Turns, scales and moves a garment's rest positions (`mesh.V`) as `options` say, in that order: what
/// importGarmentObj does to the OBJ's positions, for a garment read with a cage file.
void placeGarment(Garment& garment, const ObjImportOptions& options);

/// Reads an OBJ with per-corner UVs (`f v/vt ...`, several `vt` per vertex along seams; polygons are fan-triangulated
/// as core::readMesh does) and builds the whole garment with no cage file:
///  - layouts: the UV islands (faces joined across edges whose two corners share their UVs on both faces), each its own
///    pattern space. An island holding a vertex twice (a tube sleeve cut along its underarm) is split first along its
///    OBJ groups, else cut in two along the cheapest interior edge path through its middle (between the midpoints of
///    the two boundary stretches farthest from where it holds vertices twice, edges costing more the nearer they run
///    to those vertices: for a sleeve, its top); the cut becomes a seam between the two new layouts.
///  - panels: the OBJ's groups (`g`, else `o`, else `usemtl`, the first with two or more names) within each layout,
///    else the layouts themselves.
///  - seams: mesh edges between two panels, as chains split where three panels meet, at the boundary and where the
///    pattern outline turns by more than 45 degrees in UV; `joinsLayouts` when the two sides lie in different layouts.
///  - openings: the boundary loops, cloth on their left.
///  - names by where the pieces sit (metres, Y up, body facing +Z, x to the wearer's left), matching the body cage
///    (cage/body_cage.h): openings `hem` (lowest loop around the centre line), `neckline` (highest such loop, narrower
///    than the garment at its height), `waist` (that loop when it is as wide as the garment: a skirt),
///    `sleeve_hem_left/right` (outermost loops above the hem), `leg_hem_left/right` (side loops of a garment without a
///    hem), `outline` (the only loop); panels `front` / `back` (those touching the hem or the top loop, by their mean
///    normal), `left_sleeve` or `left_sleeve_front` / `left_sleeve_back`, ... (those reached from a sleeve hem); seams
///    `side_left`, `shoulder_left`, `sleeve_top_left`, `underarm_left` (front to back), `armhole_front_left`, ...
///    (sleeve to torso); layouts after their largest panel. Anything that fits no rule gets a neutral unique name
///    (`panel_3` or its OBJ group's name, `seam_3`, `opening_2`), so skirts and trousers import too. A garment with one
///    panel names it (and its layout) after the garment.
///  - fixes, each with a note in `report`: faces pointing into the garment are turned round; an island whose UVs run
///    clockwise is mirrored; an island whose UVs are not metres of cloth (its median edge is outside 0.9 to 1.1 times
///    as long in 3D as in UV: normalised UVs, a packed atlas) is rescaled to the 3D area of its faces.
/// The result is checked by exactly the checks of importGarment. Throws `InputError` naming the file and what was
/// expected for: anything core::readMesh refuses (malformed lines, with their line numbers), no UVs, a garment lying
/// along z ("use --up z") or outside 0.05 to 3 m tall (with the scale that would fix it, "use --scale 0.01"), unwelded
/// seams (two boundary edges at the same place), two openings touching at a vertex, an island whose UVs are folded
/// (triangles of both orientations) or overlap themselves (naming the island and a face), an island holding a vertex
/// twice that cannot be cut in two.
Garment importGarmentObj(const std::filesystem::path& obj, const ObjImportOptions& options = {},
                         ObjImportReport* report = nullptr);

/// How exportGarmentObj writes a garment, to make files like the ones users have.
struct ObjExportOptions {
  bool groups = false;  ///< write `g <panel>` lines
  /// Re-lay each sleeve's front and back halves as one UV island joined along the sleeve top (the back half reflected
  /// across the sleeve-top line, its seam vertices snapped onto the front half's), cut along the underarm: the
  /// underarm vertices have two UVs in one island. Needs the T-shirt's panels (`left_sleeve_front`, ...) and seams
  /// (`sleeve_top_left`, ...).
  bool tubeSleeves = false;
  bool separatePanels = false;  ///< each panel its own UV island (seams inside a layout become island boundaries)
  double uvScale = 1.0;         ///< UVs multiplied by this
  /// Positions written so that importGarmentObj with the same up, scale and translate gives the garment back: the file
  /// holds turn^-1((V - translate) / scale), turned back to Z up when up is 'z'.
  char up = 'y';
  double scale = 1.0;
  Eigen::Vector3d translate = Eigen::Vector3d::Zero();
  /// 0: vertices and faces in the mesh's order; otherwise vertices, faces and each face's first corner in a random
  /// order drawn from this seed (so that tests do not depend on our vertex order).
  std::uint32_t shuffleSeed = 0;
  /// Throws `InputError` naming the field out of range.
  void validate() const;
};

/// Writes `garment` as an OBJ with per-corner UVs, atomically: one `vt` per vertex and UV island, the islands (layouts,
/// or as the options say) side by side in UV without overlapping. Throws `InputError` for invalid options or, with
/// `tubeSleeves`, a garment without the T-shirt's sleeve panels and seams.
void exportGarmentObj(const Garment& garment, const std::filesystem::path& obj, const ObjExportOptions& options = {});

}  // namespace pixelcloth::garment
