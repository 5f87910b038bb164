#include "pixelcloth/motion/clip.h"

#include <assimp/config.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <map>

#include "clip_check.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::motion {

namespace fs = std::filesystem;

namespace {

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return out;
}

/// The rotation of a transform that may carry scale: the orthonormal factor of its upper 3x3 (polar decomposition).
Eigen::Matrix3d rotationOf(const Eigen::Matrix4d& m) { return Eigen::Affine3d(m).rotation(); }

/// A node's local transform at `tick` from its keys (linear between position and scale keys, spherical between
/// rotation keys, held before the first and after the last); a kind of key the channel lacks comes from `rest`.
Eigen::Matrix4d sampleChannel(const aiNodeAnim& channel, double tick, const Eigen::Matrix4d& rest) {
  const Eigen::Affine3d restAffine(rest);
  Eigen::Vector3d translation = restAffine.translation();
  Eigen::Matrix3d rotation = restAffine.rotation();
  Eigen::Vector3d scale = (restAffine.linear().transpose() * restAffine.rotation()).diagonal();
  // The bracketing keys of `tick` and the weight of the later one.
  auto bracket = [tick](const auto* keys, unsigned count) {
    unsigned hi = 0;
    while (hi < count && keys[hi].mTime < tick) ++hi;
    if (hi == 0) return std::tuple<unsigned, unsigned, double>{0, 0, 0.0};
    if (hi == count) return std::tuple<unsigned, unsigned, double>{count - 1, count - 1, 0.0};
    const double span = keys[hi].mTime - keys[hi - 1].mTime;
    return std::tuple<unsigned, unsigned, double>{hi - 1, hi, span > 0 ? (tick - keys[hi - 1].mTime) / span : 1.0};
  };
  auto vec = [](const aiVector3D& v) { return Eigen::Vector3d(v.x, v.y, v.z); };
  if (channel.mNumPositionKeys > 0) {
    const auto [a, b, w] = bracket(channel.mPositionKeys, channel.mNumPositionKeys);
    translation = (1 - w) * vec(channel.mPositionKeys[a].mValue) + w * vec(channel.mPositionKeys[b].mValue);
  }
  if (channel.mNumRotationKeys > 0) {
    const auto [a, b, w] = bracket(channel.mRotationKeys, channel.mNumRotationKeys);
    auto quat = [](const aiQuaternion& q) { return Eigen::Quaterniond(q.w, q.x, q.y, q.z); };
    const Eigen::Quaterniond qa = quat(channel.mRotationKeys[a].mValue), qb = quat(channel.mRotationKeys[b].mValue);
    // A zero quaternion stays zero (and is refused by the caller as not finite) rather than normalised to NaN here.
    const Eigen::Quaterniond q =
        qa.norm() > 0 && qb.norm() > 0 ? qa.normalized().slerp(w, qb.normalized()) : Eigen::Quaterniond(0, 0, 0, 0);
    rotation = q.norm() > 0 ? q.toRotationMatrix() : Eigen::Matrix3d::Constant(std::nan(""));
  }
  if (channel.mNumScalingKeys > 0) {
    const auto [a, b, w] = bracket(channel.mScalingKeys, channel.mNumScalingKeys);
    scale = (1 - w) * vec(channel.mScalingKeys[a].mValue) + w * vec(channel.mScalingKeys[b].mValue);
  }
  Eigen::Matrix4d out = Eigen::Matrix4d::Identity();
  out.topLeftCorner<3, 3>() = rotation * scale.asDiagonal();
  out.topRightCorner<3, 1>() = translation;
  return out;
}

/// The key spacing of the channel with the most rotation keys, in ticks, when its keys are evenly spaced; else 0.
double evenKeySpacing(const aiAnimation& animation) {
  const aiNodeAnim* longest = nullptr;
  for (unsigned c = 0; c < animation.mNumChannels; ++c)
    if (!longest || animation.mChannels[c]->mNumRotationKeys > longest->mNumRotationKeys)
      longest = animation.mChannels[c];
  if (!longest || longest->mNumRotationKeys < 2) return 0;
  const aiQuatKey* keys = longest->mRotationKeys;
  const unsigned n = longest->mNumRotationKeys;
  const double step = (keys[n - 1].mTime - keys[0].mTime) / (n - 1);
  if (!(step > 0)) return 0;
  for (unsigned k = 1; k < n; ++k)
    if (std::abs(keys[k].mTime - keys[k - 1].mTime - step) > 1e-3 * step) return 0;
  return step;
}

}  // namespace

int Clip::find(const std::string& name) const {
  const auto it = std::find(joints.begin(), joints.end(), name);
  return it == joints.end() ? -1 : static_cast<int>(it - joints.begin());
}

std::vector<int> Clip::children(int j) const {
  std::vector<int> out;
  for (int c = 0; c < static_cast<int>(parents.size()); ++c)
    if (parents[c] == j) out.push_back(c);
  return out;
}

Clip readClip(const fs::path& path, const ClipOptions& options) {
  const std::string file = path.string();
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_regular_file(path, ec), file << ": no such motion clip (expected a BVH, FBX, glTF, GLB or "
                                                          "Collada file)");
  PIXELCLOTH_CHECK(options.fps == 0 || (std::isfinite(options.fps) && options.fps >= 1 && options.fps <= 1000),
                   file << ": sampling at " << options.fps << " frames per second, expected 1 to 1000");
  detail::checkBeforeAssimp(path);
  Assimp::Importer importer;
  // FBX pivots folded into the nodes' own transforms, so every joint is one node of the hierarchy.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  const aiScene* scene = importer.ReadFile(file, 0);
  PIXELCLOTH_CHECK(scene && scene->mRootNode,
                   file << ": not a motion clip assimp can read (" << importer.GetErrorString()
                        << "); expected a BVH, FBX, glTF, GLB or Collada file with an animation");
  PIXELCLOTH_CHECK(scene->mNumAnimations > 0, file << ": holds no animation, expected a motion clip");
  PIXELCLOTH_CHECK(options.animation >= 0 && options.animation < static_cast<int>(scene->mNumAnimations),
                   file << ": animation " << options.animation << ", the file holds " << scene->mNumAnimations);
  const aiAnimation& animation = *scene->mAnimations[options.animation];

  Clip clip;
  clip.source = file;
  clip.animation = animation.mName.C_Str();
  // The hierarchy, parents first, with each node's rest (file) transform.
  std::vector<const aiNode*> nodes;
  std::vector<Eigen::Matrix4d> restLocal;
  std::vector<std::pair<const aiNode*, int>> stack = {{scene->mRootNode, -1}};
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    const int index = static_cast<int>(nodes.size());
    nodes.push_back(node);
    clip.joints.emplace_back(node->mName.C_Str());
    clip.parents.push_back(parent);
    restLocal.push_back(toEigen(node->mTransformation));
    for (unsigned c = node->mNumChildren; c-- > 0;) stack.emplace_back(node->mChildren[c], index);
  }
  const int J = static_cast<int>(nodes.size());
  std::map<std::string, const aiNodeAnim*> channels;
  int maxKeys = 0;
  for (unsigned c = 0; c < animation.mNumChannels; ++c) {
    const aiNodeAnim* channel = animation.mChannels[c];
    channels[channel->mNodeName.C_Str()] = channel;
    maxKeys = std::max<int>(maxKeys, std::max({channel->mNumRotationKeys, channel->mNumPositionKeys}));
  }
  PIXELCLOTH_CHECK(maxKeys > 0, file << ": the animation has no frames");
  // assimp reads a BVH of "Frames: 0" as one key and a duration of 2^32 - 1 ticks.
  const double ticks = animation.mTicksPerSecond > 0 ? animation.mTicksPerSecond : 25.0;
  PIXELCLOTH_CHECK(
      std::isfinite(animation.mDuration) && animation.mDuration >= 0 && animation.mDuration / ticks <= 7 * 24 * 3600,
      file << ": the animation lasts " << animation.mDuration << " ticks at " << ticks
           << " per second; expected frames (a BVH needs Frames: 1 or more)");
  for (const auto& [name, channel] : channels)
    PIXELCLOTH_CHECK(std::find(clip.joints.begin(), clip.joints.end(), name) != clip.joints.end(),
                     file << ": the animation moves a joint '" << name << "' that the hierarchy lacks");

  // Frame times: the keys' own rate when they are evenly spaced, else the rate asked for (30 by default).
  const double ticksPerSecond = ticks;
  const double spacing = evenKeySpacing(animation);
  const double keyRate = spacing > 0 ? ticksPerSecond / spacing : 0;
  clip.fps = options.fps > 0 ? options.fps : keyRate > 0 ? keyRate : 30.0;
  PIXELCLOTH_CHECK(std::isfinite(clip.fps) && clip.fps >= 1 && clip.fps <= 1000,
                   file << ": " << clip.fps << " frames per second (its key spacing), expected 1 to 1000");
  double first = 0, last = 0;
  bool anyKey = false;
  for (const auto& [name, channel] : channels) {
    for (unsigned k = 0; k < channel->mNumRotationKeys; ++k) {
      const double t = channel->mRotationKeys[k].mTime;
      first = anyKey ? std::min(first, t) : t;
      last = anyKey ? std::max(last, t) : t;
      anyKey = true;
    }
  }
  PIXELCLOTH_CHECK(anyKey && std::isfinite(first) && std::isfinite(last) && last >= first,
                   file << ": the animation's rotation keys have no valid times");
  const double seconds = (last - first) / ticksPerSecond;
  const double frameCount = std::floor(seconds * clip.fps + 1e-6) + 1;
  PIXELCLOTH_CHECK(frameCount <= 1e6, file << ": " << frameCount << " frames, expected at most a million");
  const int frames = static_cast<int>(frameCount);

  auto world = [&](const std::vector<Eigen::Matrix4d>& local) {
    std::vector<Eigen::Matrix4d> out(J);
    for (int j = 0; j < J; ++j) out[j] = clip.parents[j] < 0 ? local[j] : out[clip.parents[j]] * local[j];
    return out;
  };
  const std::vector<Eigen::Matrix4d> rest = world(restLocal);
  clip.restPositions.resize(J, 3);
  for (int j = 0; j < J; ++j) {
    PIXELCLOTH_CHECK(rest[j].allFinite(), file << ": joint '" << clip.joints[j] << "': rest transform is not finite");
    clip.restPositions.row(j) = rest[j].topRightCorner<3, 1>().transpose();
    clip.restRotations.push_back(rotationOf(rest[j]));
  }
  clip.rotations.resize(frames);
  clip.positions.resize(frames);
  std::vector<Eigen::Matrix4d> local = restLocal;
  for (int f = 0; f < frames; ++f) {
    const double tick = first + f / clip.fps * ticksPerSecond;
    for (int j = 0; j < J; ++j) {
      const auto it = channels.find(clip.joints[j]);
      local[j] = it == channels.end() ? restLocal[j] : sampleChannel(*it->second, tick, restLocal[j]);
      PIXELCLOTH_CHECK(local[j].allFinite(), file << ": joint '" << clip.joints[j] << "', frame " << f
                                                  << ": its rotation or position is not finite");
    }
    const std::vector<Eigen::Matrix4d> posed = world(local);
    clip.rotations[f].resize(J);
    clip.positions[f].resize(J, 3);
    for (int j = 0; j < J; ++j) {
      clip.rotations[f][j] = rotationOf(posed[j]);
      clip.positions[f].row(j) = posed[j].topRightCorner<3, 1>().transpose();
    }
  }
  return clip;
}

}  // namespace pixelcloth::motion
