#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/mesh.h"

namespace pixelcloth::body {

/// One collision part of the body (DESIGN.md "Body"): a subset of faces that overlaps its neighbours
/// around the shoulders, so every cloth vertex can collide against its primary part alone.
struct BodyPart {
  std::string name;           ///< "left_arm", "right_arm" or "torso"
  std::vector<int> faces;     ///< face indices into the body mesh
  std::vector<int> vertices;  ///< vertices used by those faces, sorted
};

/// A skinned body: closed manifold mesh in the rest T-pose, skeleton, skin weights, collision parts.
struct Body {
  core::Mesh mesh;              ///< rest T-pose, metres
  Skeleton skeleton;            ///< rest joints
  Eigen::MatrixXd weights;      ///< #V x #J skin weights, non-negative, rows sum to 1
  std::vector<BodyPart> parts;  ///< left_arm, right_arm, torso

  /// Posed vertex positions (#V x 3) by linear blend skinning.
  Eigen::MatrixX3d posedVertices(const Pose& pose) const;
  /// The posed mesh: posed vertices, the same faces.
  core::Mesh posedMesh(const Pose& pose) const;
  /// Throws InputError if sizes disagree, weights are negative / not normalised, or the mesh is not closed.
  void validate(const std::string& context = "body") const;
};

/// Options of the built-in mannequin.
struct MannequinOptions {
  double shape = 0.0;          ///< girth in [-1, 2]: -1 thinner, 0 default, 2 thicker (paper's modified body shapes)
  double edgeLength = 0.0075;  ///< target triangle size, metres (about 15K vertices at the default)
  /// Throws InputError when an option is out of range.
  void validate() const;
};

/// The built-in upper-body mannequin (1.75 m, T-pose): head, neck, torso to the hips, arms with hands.
/// The surface is the zero set of a smooth union of round cones and ellipsoids, meshed by CGAL's
/// surface mesher (Boissonnat-Oudot), so it is closed, manifold and smooth; skin weights by bone heat.
Body makeMannequin(const MannequinOptions& options = {});

/// The rest skeleton of the mannequin (independent of its shape parameter).
Skeleton mannequinSkeleton();

/// Options of the automatic skin weights.
struct SkinWeightOptions {
  /// Pinocchio's c: heat H = c / d^2 towards the nearest visible bone. Pinocchio uses 1; 2 keeps an
  /// arm's influence off the far side of the torso (measured: left-arm weight 0 for x < -8 cm) while
  /// weights still change by at most ~0.2 across an edge of the default mannequin.
  double heatScale = 2.0;
  double minimumWeight = 0.01;  ///< weights below this are dropped before renormalising
  void validate() const;
};

/// Automatic skin weights by bone heat (Baran and Popovic 2007, "Automatic rigging and animation of 3D
/// characters"): per joint j, solve (-L + M H) w_j = M H p_j on the closed mesh, where L is the
/// cotangent Laplacian, M the lumped mass, H the heat of the nearest bone visible from the vertex
/// (segment test against the mesh, CGAL AABB tree) and p_j = 1 where that bone is j's.
/// `V` #V x 3, `F` #F x 3 closed mesh; returns #V x #J, non-negative, rows summing to 1.
Eigen::MatrixXd boneHeatWeights(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Skeleton& skeleton,
                                const SkinWeightOptions& options = {});

/// The paper's skinning-artifact experiment: moves `fraction` of each upper-arm vertex's arm weight
/// to the torso (`torso`: to spine1) or half to the torso and half to the opposite arm (`torso+arm`).
/// Returns the corrupted weights (rows still sum to 1).
Eigen::MatrixXd corruptUpperArmWeights(const Skeleton& skeleton, const Eigen::MatrixXd& weights,
                                       const std::string& mode, double fraction = 0.5);

/// Splits the body into the three overlapping collision parts from its skin weights: an arm part
/// takes every face touching a vertex whose arm weight (arm + forearm) exceeds `overlap`; the torso
/// takes every face touching a vertex whose total arm weight is below 1 - `overlap`. Faces with arm
/// weights between the two (around the shoulders) belong to both.
std::vector<BodyPart> collisionParts(const Body& body, double overlap = 0.25);

/// For each part, the parts it meets (shares a body vertex with: the overlap around the shoulders), in part order.
std::vector<std::vector<int>> meetingParts(const std::vector<BodyPart>& parts);

/// Joint positions given by a user for an imported body, by joint name (metres).
using JointPositions = std::map<std::string, Eigen::Vector3d>;

/// Where the 10 posable joints of `body` are in `pose`, by name: what importBody expects for a body standing so.
JointPositions posedJoints(const Body& body, const Pose& pose);

/// Reads joint positions from JSON: either {"joints": {"l_arm": [x, y, z], ...}} or the same object at
/// the top level. Required: the 10 posable joints; optional: root, head, l_hand, r_hand (hand tips).
JointPositions readJointPositions(const std::filesystem::path& path);

/// Options of importBody.
struct ImportOptions {
  /// Keep only the mesh's largest component (most faces), dropping separate shells such as eyes, teeth or
  /// accessories that downloaded human models often have. Without it a mesh of several components is refused.
  bool largestComponent = false;
};

/// Imports a body: `mesh` in metres (its bounding box's largest side 0.5 to 2.5 m, else InputError suggesting the
/// units it seems to be in), one closed manifold component (else InputError naming `context`, the first problem's
/// vertices counted from 1 and the component it is on; see ImportOptions::largestComponent), standing in a T- or
/// A-pose, joints inside the mesh. Fits the skeleton (missing optional joints estimated from the mesh),
/// computes bone-heat weights, and brings arms that hang below the horizontal into the T-pose by
/// rotating the arm joints; returns the body in its T-pose.
Body importBody(const core::Mesh& mesh, const JointPositions& joints, const std::string& context = "body",
                const ImportOptions& options = {});

/// Writes a body folder: body.obj, skeleton.json (joints, parents, rest positions, bone ends, limits,
/// pose order), weights.npy (#V x #J float32), parts.json. Each file atomically.
void saveBody(const std::filesystem::path& folder, const Body& body, const std::string& description = {});
/// Reads a folder written by saveBody and checks it (vertex count of weights vs mesh, skeleton, parts).
Body loadBody(const std::filesystem::path& folder);

}  // namespace pixelcloth::body
