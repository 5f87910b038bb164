#pragma once

// One binary glTF (.glb) of a predicted sequence, for Blender, game engines and web viewers: the body as a skinned
// mesh whose 12 joints are animated (the pose's local rotations, the clip's root motion on the root), and the garment
// as a mesh with one morph target per frame, its weights keyed so that each frame shows its own shape.

#include <Eigen/Core>
#include <filesystem>
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

}  // namespace pixelcloth::motion
