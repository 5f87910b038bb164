#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/core/image.h"
#include "pixelcloth/core/mesh.h"

namespace pixelcloth::garment {

/// An ordered chain of garment vertices along mesh edges where pieces are sewn (a cage curve of the
/// paper's section 3). Consecutive vertices share a mesh edge.
struct Seam {
  std::string name;  ///< "side_left", "underarm_left", "shoulder_left", "sleeve_top_left", "armhole_front_left", ...
  std::vector<int> vertices;  ///< ordered chain of mesh vertex indices (rows of `Garment::mesh.V`)
  /// true: the chain lies on the boundary of both the front and the back layout (stitched: one 3D vertex with two
  /// UVs, one per layout); false: a sewn line inside one layout (the armholes).
  bool joinsLayouts = false;
};

/// An unsewn boundary loop of the garment (hem, neckline, sleeve hem, the necktie's outline). The vertices are ordered
/// along the boundary with the cloth on the left seen from outside; the loop closes from the last back to the first.
struct Opening {
  std::string name;
  std::vector<int> vertices;
};

/// What a cage curve is (paper section 3): a sewn seam, a body loop (chest, waist, bicep), a centre line, a garment
/// opening (hem, neckline, sleeve hem), or another line that splits patches. The garment's cage (cage/cage.h) and its
/// cage lines (CageLine) share it.
enum class CurveKind { Seam, Loop, CentreLine, Opening, Split };

/// "seam", "loop", "centre_line", "opening", "split": how garment.json and cage.json spell the kinds.
const char* curveKindName(CurveKind kind);
/// Inverse of curveKindName; throws `InputError` prefixed with `context` listing the names.
CurveKind curveKindFromName(const std::string& name, const std::string& context);

/// A cage line that is neither a seam nor an opening (DESIGN.md, "Cage"): a body loop around the torso or a sleeve,
/// a centre line, or a line that only splits a region too large for one patch. The pattern mesher inserts it as a
/// constraint, so it runs along mesh edges: consecutive vertices (and last-first when closed) share a mesh edge.
/// T-shirt lines:
///  - "chest", "waist" (kind Loop, closed): horizontal lines across the front and the back torso, joined through the
///    side seams into one loop; "bicep_left", "bicep_right" (loop, closed): across both sleeve halves at mid-sleeve,
///    joined through the sleeve-top and underarm seams. Each loop runs from the wearer's right (or the underarm) along
///    the front, then back along the back layout.
///  - "centre_front", "centre_back" (kind CentreLine, open): neckline to hem.
///  - "side_panel_front_left", "side_panel_front_right", "side_panel_back_left", "side_panel_back_right" (kind
///    Split, open): vertical lines from the chest line to the hem; left/right are the wearer's.
/// Necktie lines: "tie_band_1" (lowest) ... (kind Split, open), across the blade from edge to edge.
struct CageLine {
  std::string name;
  CurveKind kind = CurveKind::Split;  ///< Loop, CentreLine or Split
  std::vector<int> vertices;  ///< ordered chain of mesh vertex indices
  bool closed = false;        ///< continues from the last vertex back to the first
};

/// How the flat pattern was meshed: what the seam matching and the vertex-count search needed.
struct PatternMeshingStats {
  int stitchRounds = 0;        ///< mesh-and-compare rounds until the stitched seams agreed, for the kept mesh
  int sizeTrials = 0;          ///< edge-length bounds tried to reach the target vertex count
  double maxEdgeLength = 0;    ///< edge length bound handed to the mesher, metres of pattern space
  double minAngleDegrees = 0;  ///< smallest triangle angle in pattern space
  double seconds = 0;          ///< wall time of the whole construction
  /// One line, e.g. "3012 vertices, min angle 20.8 deg, 3 stitch rounds, 2 size trials, 0.21 s".
  std::string summary(int numVertices) const;
};

/// What the later stages need to know about a garment besides its mesh and cage, carried by the garment (and its
/// garment.json, field "traits") so that no stage looks a garment up by name. Defaults: a garment worn on the torso and
/// arms, the paper's T-shirt settings.
struct GarmentTraits {
  /// Joints of the pose vector that drive the garment: the first `poseJoints` of body::kPoseJoints, 9 floats each
  /// (DESIGN.md, "Pose vector"). 10 (90 floats) for garments on the arms; 4 (the centre line, 36 floats) for the
  /// necktie, which hangs from the neck (paper section 6). Sampled poses keep the other joints at rest, and arm poses
  /// are pruned against the torso only when an arm joint drives the garment.
  int poseJoints = 10;
  /// Vertices held at their skinned rest position by the simulation (the necktie's knot end), rows of `mesh.V`.
  std::vector<int> pinned;
  /// Whole-garment cloth image per layout, pixels (paper appendix: 256 x 256 for the T-shirt, 64 x 256 for the tie).
  int imageWidth = 256;
  int imageHeight = 256;
  /// Learn offsets in the root frame rather than in the embedded local frames by default (the paper's necktie).
  bool rootFrameOffsets = false;
  double normalLossWeight = 0.01;  ///< the paper's normal-loss weight for this garment (0.1 for the necktie)
  double edgeLossWeight = 0.0;     ///< the paper's edge-length loss weight (0.1 for the necktie, 0 for the T-shirt)

  /// Floats of the pose vector the garment's data holds: 9 * poseJoints.
  int poseSize() const { return 9 * poseJoints; }
  /// true when an arm joint (l_shoulder onwards) drives the garment.
  bool armsDrive() const { return poseJoints > 4; }
  /// Throws `InputError` prefixed with `context` naming the field out of range (pinned vertices must be < numVertices).
  void validate(int numVertices, const std::string& context) const;
  /// {"pose_joints": [names], "pinned": [...], "image_size": [w, h], "offset_frame": "local" | "root",
  ///  "normal_loss_weight", "edge_loss_weight"}.
  nlohmann::json toJson() const;
  /// Reads what toJson writes; absent fields keep their defaults. "pose_joints" must name a prefix of
  /// body::kPoseJoints. Validates against `numVertices`; `context` (a file name) prefixes messages.
  static GarmentTraits fromJson(const nlohmann::json& json, int numVertices, const std::string& context);
};

/// A garment template: one triangle mesh sewn from flat pattern pieces, each vertex a cloth pixel with fixed
/// coordinates in pattern space (per layout). Pattern space: metres, u to the right and v up as the layout is drawn.
struct Garment {
  std::string name;  ///< "tshirt", "necktie" (the templates) or the name an imported garment was given; for people
  /// V: #V x 3 rest placement around the T-posed mannequin, metres (Y up, body faces +Z), faces oriented outwards;
  /// F: #F x 3; UV / FUV: per-corner pattern coordinates in metres, each layout's triangles counter-clockwise.
  core::Mesh mesh;
  std::vector<std::string> layouts;  ///< {"front", "back"} for the T-shirt, {"tie"} for the necktie
  Eigen::VectorXi faceLayout;        ///< #F, index into `layouts`
  std::vector<std::string> panels;   ///< pattern pieces; T-shirt: front, back, left_sleeve_front, left_sleeve_back, ...
  Eigen::VectorXi facePanel;         ///< #F, index into `panels`
  /// #V x #layouts: row of `mesh.UV` that vertex v has in layout l, or -1 where v is not part of that layout.
  /// Vertices on stitched seams have one UV in each layout.
  Eigen::MatrixXi vertexUV;
  /// The pattern position of vertex v in layout l (`mesh.UV` at vertexUV(v, l), which must not be -1).
  Eigen::Vector2d uvOf(int v, int layout) const { return mesh.UV.row(vertexUV(v, layout)).transpose(); }
  std::vector<Seam> seams;
  std::vector<Opening> openings;
  std::vector<CageLine> lines;  ///< cage lines other than seams and openings (see CageLine)
  PatternMeshingStats meshing;
  GarmentTraits traits;
  /// How a template was built, {"name": "tshirt", "options": {every TShirtOptions field}} (or the necktie's), so that
  /// loading its folder rebuilds the exact mesh rather than the OBJ's rounded numbers; null for an imported garment.
  nlohmann::json recipe;

  int numLayouts() const { return static_cast<int>(layouts.size()); }
  /// Index of a layout by name; throws `InputError` naming the known layouts if there is none.
  int layoutIndex(const std::string& layoutName) const;
  /// Bounding box of the UVs used by the faces of one layout, metres of pattern space.
  Eigen::AlignedBox2d layoutBounds(int layout) const;
  /// Vertical extent of the first layout, metres: for the T-shirt the front from the neck-side point to the hem, for
  /// the necktie its length.
  double length() const;
  /// Seam by name, or nullptr.
  const Seam* findSeam(const std::string& seamName) const;
  /// Cage line by name, or nullptr.
  const CageLine* findLine(const std::string& lineName) const;
  /// One line: "tshirt: 3012 vertices, 5790 faces, layouts front+back, 6 panels, 12 seams, 4 openings, 10 cage lines".
  std::string summary() const;
};

/// A plain short-sleeve T-shirt for the built-in 1.75 m mannequin (arms horizontal at shoulder height). Lengths in
/// metres of pattern space, measured on the front layout with x to the wearer's left and y up from the hem.
struct TShirtOptions {
  int targetVertices = 3000;        ///< vertex count of the stitched mesh to aim for (reached within a few percent)
  double length = 0.67;             ///< neck-side point to hem
  double halfWidth = 0.27;          ///< body half-width (chest half-width ~0.165 plus ease)
  double shoulderHalfWidth = 0.20;  ///< centre line to the shoulder point (top of the armhole)
  double shoulderDrop = 0.01;       ///< how much lower the shoulder point is than the neck-side point
  /// Armpit (bottom of the armhole) below the neck-side point. Deep enough for raised and forward arms: at 0.19 the
  /// underarm corner more than doubled its area in a quarter of the sampled poses; 0.25 with the 0.23 sleeve hem
  /// keeps 84% of 576 sampled poses against 79% at 0.23 / 0.19 (docs/simulation.md).
  double armpitDepth = 0.25;
  double sleeveLength = 0.21;       ///< shoulder point to sleeve hem along the sleeve's top line
  double sleeveHemHeight = 0.23;    ///< flat height of the sleeve hem (half its circumference)
  double neckHalfWidth = 0.08;      ///< centre line to the neck-side point
  double frontNeckDepth = 0.09;     ///< front neckline depth below the neck-side point
  double backNeckDepth = 0.02;      ///< back neckline depth below the neck-side point
  double neckSideHeight = 1.48;     ///< height of the neck-side point in the rest placement
  double torsoDepth = 0.12;         ///< distance of the front (back) torso from the side seams' plane z = 0
  /// Height above the hem of the chest loop (below the armpit). With the waist height it sets the three bands of the
  /// torso; 0.41 / 0.215 keep the two lower bands within 128 px of the 512 px cloth image (patches/frame.h).
  double chestHeight = 0.41;
  double waistHeight = 0.215;  ///< height above the hem of the waist loop
  double sidePanelX = 0.15;    ///< distance of the side-panel split lines (chest line to hem) from the centre line
  double bicepFraction =
      0.5;                    ///< where the bicep loops cross the sleeve-top and underarm seams, fraction from the body
  double sleeveDepth = 0.06;  ///< same for the sleeves
  /// Spacing of the first samples along the pattern's outline and seams, relative to the mesher's edge-length bound.
  /// About 0.7 matches the interior edge length; larger values let the mesher split boundary edges where it needs
  /// to, and the seams are then matched across the layouts in more rounds. In [0.3, 3].
  double boundarySpacing = 0.7;
  /// Throws `InputError` naming the field when an option is out of range or the pattern pieces would not fit.
  void validate() const;
  /// The same shirt graded by `factor`: every length of the pattern (widths, lengths, depths, the neck, the sleeves,
  /// the loop and split heights) times `factor`, the placement height (neckSideHeight), the mesh size and the
  /// fractions kept. Proportional grading, as a pattern is graded between sizes. Throws `InputError` unless `factor`
  /// is in [0.6, 1.6].
  TShirtOptions graded(double factor) const;
};

/// The grading factor of a named size, M being the default template (1.0): XS 0.88, S 0.94, M 1, L 1.06, XL 1.12,
/// XXL 1.18 (about one chest size, 6 cm of girth on the 1.75 m mannequin, per step). Case-insensitive; throws
/// `InputError` naming the sizes for any other name.
double sizeGrade(const std::string& size);

/// The size whose grade is nearest `grade` ("XS" ... "XXL"), for advice such as "try --size L".
std::string nearestSize(double grade);

/// Builds the T-shirt template: front and back layouts (each the body piece with the two sleeve halves, joined along
/// the armholes), triangulated in pattern space by CGAL's constrained Delaunay mesher (min angle >= 20.7 degrees),
/// stitched along the side, underarm, shoulder and sleeve-top seams. Openings: hem, neckline, sleeve_hem_left,
/// sleeve_hem_right. Cage lines (see CageLine) inserted as mesher constraints split each layout into 14 patches.
/// Deterministic.
Garment makeTShirt(const TShirtOptions& options = {});

/// A necktie blade: one narrow layout, pointed tip at the bottom, hanging flat in front of the chest.
struct NecktieOptions {
  int targetVertices = 500;      ///< vertex count to aim for
  double length = 0.44;          ///< knot end to tip, metres
  double knotWidth = 0.05;       ///< width at the knot end (top)
  double bladeWidth = 0.10;      ///< widest point, just above the tip
  double tipHeight = 0.06;       ///< height of the pointed tip below the widest point
  double topHeight = 1.45;       ///< height of the knot end in the rest placement
  double frontOffset = 0.13;     ///< z of the hanging tie in the rest placement
  double boundarySpacing = 0.7;  ///< first sample spacing along the outline relative to the edge-length bound, [0.3, 3]
  /// Number of patches along the blade, [1, 20]: bands - 1 evenly spaced cage lines "tie_band_1", ... across it (the
  /// lowest must clear the tip: length / bands > tipHeight).
  int bands = 5;
  /// Throws `InputError` naming the field when an option is out of range.
  void validate() const;
};

/// Builds the necktie template: one layout "tie", one panel, no seams, one opening "outline", bands - 1 cage lines.
/// Deterministic.
Garment makeNecktie(const NecktieOptions& options = {});

/// Writes a garment folder: garment.obj (positions, per-corner UVs as `vt`) and garment.json (layouts,
/// panels, per-face layout and panel, seams and openings as vertex chains). Each file atomically.
void saveGarment(const std::filesystem::path& folder, const Garment& garment);

// ---------------------------------------------------------------------------------------------------------------------
// Garment import: a garment folder read back, or a user's own garment brought in.

/// Reads a garment from an OBJ with per-corner texture coordinates (`vt`, pattern-space metres) and a JSON file with
/// its layouts and cage, in the schema saveGarment writes to garment.json:
///  - "name": string, required.
///  - "layouts": non-empty array of {"name": ...} objects (other fields, such as "bounds_m", are ignored) or of plain
///    strings. Each face's UVs are coordinates in its layout.
///  - "face_layout": #F layout indices (0-based, one per triangle of the mesh as core::readMesh builds it, i.e. per
///    OBJ face when the OBJ holds triangles only); optional when there is one layout, required otherwise.
///  - "panels" (array of strings) and "face_panel" (#F panel indices), optional: by default one panel named after the
///    garment; "face_panel" is required when there are two or more panels and needs "panels".
///  - "seams": [{"name", "vertices", "joins_layouts"?}], "openings": [{"name", "vertices"}], "cage_lines": [{"name",
///    "kind", "closed"?, "vertices"}]; each list optional (absent: none). "joins_layouts" is computed when absent:
///    true when the seam's edges have faces of two different layouts; "closed" defaults to false.
///  - "format", "version" and "mesh" {"vertices", "faces"} are checked against the OBJ when present; other fields
///    ("units", "meshing", ...) are ignored.
/// Vertex indices in the JSON are 0-based rows of the OBJ's vertex list, as saveGarment writes them: JSON vertex i is
/// the OBJ's `v` line number i + 1. Messages say "vertex i (OBJ vertex i + 1)" so that both can be found; faces are
/// counted from 1 in messages, as the OBJ counts them.
///
/// Builds `Garment::vertexUV` from FUV and the face layouts, `faceLayout`, `facePanel`, `seams`, `openings` and
/// `lines`; `meshing` stays default. Throws `InputError` naming the file and the field for any of:
///  - a missing or unreadable OBJ, one without texture coordinates on every face, an invalid JSON;
///  - a vertex used by no face; a vertex with two different UVs (more than 1 nm apart) in the same layout; a
///    degenerate UV triangle (height below 1e-6 of its longest edge or below 0.1 micrometre);
///  - a missing or ill-typed field, a face_layout / face_panel of the wrong length or with an index out of range, a
///    layout no face uses, names repeated within layouts, panels, seams, openings or cage lines;
///  - a polyline (seam, opening, cage line) with a vertex index out of range, a vertex visited twice, too few
///    vertices (2 when open, 3 when closed), or consecutive vertices (last-first for closed lines and openings) that
///    share no mesh edge; a cage line kind other than "loop", "centre_line", "split";
///  - an opening edge that is not a mesh boundary edge or runs against the boundary (the cloth must be on the left:
///    the opening follows the orientation of its faces); a boundary edge in no opening or in two;
///  - an edge between faces of two layouts on no seam; a "joins_layouts" contradicting the faces around the seam;
///  - a patch not closed: the faces are flood-filled across the edges on no seam, opening or cage line into patches;
///    each end of an open seam or cage line must lie on another seam, opening or cage line or on the mesh boundary
///    (a curve that stops inside a patch is refused, naming the curve and its end vertex), and every interior curve
///    edge must have different patches on its two sides.
Garment importGarment(const std::filesystem::path& obj, const std::filesystem::path& cageJson);

/// Reads a garment folder that saveGarment wrote: importGarment(folder / "garment.obj", folder / "garment.json").
Garment loadGarment(const std::filesystem::path& folder);

/// Names of the built-in garment templates, in the order the CLI lists them: {"tshirt", "necktie"}.
const std::vector<std::string>& templateNames();

/// The built-in template called `name` with default options (makeTShirt() or makeNecktie()). Throws `InputError`
/// "<context>: unknown garment template 'skirt'; expected one of: tshirt, necktie" for any other name.
Garment makeGarment(const std::string& name, const std::string& context = "garment");

/// How a template is built on request (the `garment` verb's --vertices, --size, --grade).
struct TemplateRequest {
  int vertices = 0;    ///< target vertex count; 0: the template's default (T-shirt 3000, necktie 500)
  double grade = 1.0;  ///< TShirtOptions::graded factor (sizeGrade for a named size); the necktie has one size
};

/// The built-in template called `name` built as `request` asks. Throws `InputError` for an unknown name, options out of
/// range, or a grade other than 1 for a template without sizes.
Garment makeGarment(const std::string& name, const TemplateRequest& request, const std::string& context = "garment");

/// The traits of a built-in template (what makeGarment(name).traits holds), without building its mesh; for garment
/// folders written before garment.json carried its traits. Throws like makeGarment for an unknown name.
GarmentTraits templateTraits(const std::string& name, const std::string& context = "garment");

/// What every verb's --garment takes: a template name (tshirt, necktie) or a garment folder (garment.obj +
/// garment.json, as `pixelcloth garment` writes it, template or imported). A garment folder is read as one, even when
/// it is called like a template (`pixelcloth garment tshirt --out tshirt`); a template name is the template when no
/// garment folder of that name is there; any other existing path must be a garment folder. Throws `InputError` "<context>: 'X' is neither a garment template (tshirt,
/// necktie) nor a garment folder (...)" naming what was expected.
Garment resolveGarment(const std::string& nameOrFolder, const std::string& context = "--garment");

}  // namespace pixelcloth::garment
