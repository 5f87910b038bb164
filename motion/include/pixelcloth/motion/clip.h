#pragma once

// A motion clip as it is in its file: the clip's own joint hierarchy, its rest pose and, for every frame sampled at a
// fixed rate, each joint's world rotation and position. Read through assimp (BVH, FBX, glTF/GLB, Collada), in the
// clip's own axes and units; motion/retarget.h turns it into poses of our skeleton.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace pixelcloth::motion {

struct Clip {
  std::string source;                          ///< the file it was read from
  std::string animation;                       ///< the name of the animation read (a file may hold several)
  double fps = 0;                              ///< frames per second of `rotations` and `positions`
  std::vector<std::string> joints;             ///< every node of the hierarchy, parents before children
  std::vector<int> parents;                    ///< -1 for a top node
  Eigen::MatrixX3d restPositions;              ///< #J x 3 world positions of the rest pose, in the clip's units
  std::vector<Eigen::Matrix3d> restRotations;  ///< #J world rotations of the rest pose
  std::vector<std::vector<Eigen::Matrix3d>> rotations;  ///< [frame][joint] world rotations
  std::vector<Eigen::MatrixX3d> positions;              ///< [frame] #J x 3 world positions

  int frames() const { return static_cast<int>(rotations.size()); }
  /// Index of the joint named `name`, or -1.
  int find(const std::string& name) const;
  /// The children of joint `j`, in file order.
  std::vector<int> children(int j) const;
};

struct ClipOptions {
  /// Frames per second to sample the animation at; 0: the rate of its keys when they are evenly spaced (a BVH's
  /// Frame Time), else 30.
  double fps = 0;
  /// Which animation of the file, by index.
  int animation = 0;
};

/// Reads the animation of a BVH, FBX, glTF/GLB or Collada file. Throws InputError naming the file for what assimp
/// cannot read (a malformed or truncated file, an unknown format), a file without animation or joints, zero frames, a
/// frame rate outside 1 to 1000, and rotations or positions that are not finite (the joint and frame named).
Clip readClip(const std::filesystem::path& path, const ClipOptions& options = {});

}  // namespace pixelcloth::motion
