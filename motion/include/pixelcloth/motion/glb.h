#pragma once

// One binary glTF (.glb) of a predicted sequence, for Blender, game engines and web viewers: the body as a skinned
// mesh whose 12 joints are animated (the pose's local rotations, the clip's root motion on the root), and the garment
// as a mesh with one morph target per frame, its weights keyed so that each frame shows its own shape.

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/mesh.h"

namespace pixelcloth::motion {

struct AnimatedScene {
  const body::Body* body = nullptr;
  std::vector<body::Pose> poses;                ///< per frame
  std::vector<Eigen::Matrix3d> rootRotations;   ///< per frame, about the root joint's rest position
  Eigen::MatrixX3d rootTranslations;            ///< per frame, metres
  const core::Mesh* garment = nullptr;          ///< its faces (and UVs) are used
  std::vector<Eigen::MatrixX3d> garmentFrames;  ///< per frame, world positions (the root motion applied)
  double fps = 30;
};

/// Writes `scene` as a .glb, atomically. The body's skinning keeps each vertex's four largest weights (renormalised).
/// Throws InputError for frame counts that disagree or positions that are not finite.
void writeAnimatedGlb(const std::filesystem::path& path, const AnimatedScene& scene);

/// One mesh of a plain .glb scene (meshesGlb): triangles in one or more frames, with optional colour sets.
struct GlbMesh {
  std::string name;
  Eigen::MatrixX3i faces;
  std::vector<Eigen::MatrixX3d> frames;  ///< at least one; every frame #V x 3, metres
  /// Per-vertex RGB in [0, 1] (#V x 3), each written as a vertex attribute: "COLOR_0" is glTF's vertex colour, a
  /// name starting with "_" is an application attribute (three.js reads "_ERROR" as "_error").
  std::map<std::string, Eigen::MatrixX3f> colors;
};

/// The bytes of a .glb holding `meshes`, one node each, named as the mesh. A mesh of several frames holds frame 0 and
/// one morph target per later frame, with an animation "frames" at `fps` that shows each frame in turn (as
/// writeAnimatedGlb keys the garment). Throws InputError for a mesh without frames, frames of different sizes,
/// positions that are not finite, or a colour set of another size.
std::string meshesGlb(const std::vector<GlbMesh>& meshes, double fps = 30);

}  // namespace pixelcloth::motion
