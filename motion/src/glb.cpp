#include "pixelcloth/motion/glb.h"

#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstring>
#include <numeric>
#include <sstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::motion {

namespace {

/// Appends typed data to the model's one buffer as a buffer view and an accessor of it; returns the accessor.
class GltfWriter {
 public:
  explicit GltfWriter(tinygltf::Model& model) : model_(model) { model_.buffers.resize(1); }

  template <typename T>
  int accessor(const std::vector<T>& values, int componentType, int type, size_t count, int target = 0) {
    std::vector<unsigned char>& data = model_.buffers[0].data;
    while (data.size() % 4) data.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = values.size() * sizeof(T);
    view.target = target;
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    data.insert(data.end(), bytes, bytes + view.byteLength);
    model_.bufferViews.push_back(view);
    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model_.bufferViews.size()) - 1;
    accessor.componentType = componentType;
    accessor.type = type;
    accessor.count = count;
    model_.accessors.push_back(accessor);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  /// float VEC3 positions (or deltas) with the min and max glTF asks of POSITION accessors.
  int positions(const Eigen::MatrixX3d& P) {
    std::vector<float> values(P.size());
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      for (int c = 0; c < 3; ++c) values[3 * i + c] = static_cast<float>(P(i, c));
    const int a =
        accessor(values, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, P.rows(), TINYGLTF_TARGET_ARRAY_BUFFER);
    for (int c = 0; c < 3; ++c) {
      model_.accessors[a].minValues.push_back(static_cast<float>(P.col(c).minCoeff()));
      model_.accessors[a].maxValues.push_back(static_cast<float>(P.col(c).maxCoeff()));
    }
    return a;
  }

  /// Triangle indices, 16-bit when every vertex index fits (half the bytes).
  int indices(const Eigen::MatrixX3i& F, Eigen::Index vertices) {
    if (vertices <= 65535) return indexAccessor<std::uint16_t>(F, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    return indexAccessor<std::uint32_t>(F, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  }

  template <typename Index>
  int indexAccessor(const Eigen::MatrixX3i& F, int componentType) {
    std::vector<Index> values(F.size());
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int c = 0; c < 3; ++c) values[3 * f + c] = static_cast<Index>(F(f, c));
    return accessor(values, componentType, TINYGLTF_TYPE_SCALAR, values.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  }

  int floats(const std::vector<float>& values, int type, size_t count) {
    return accessor(values, TINYGLTF_COMPONENT_TYPE_FLOAT, type, count);
  }

  int colors(const Eigen::MatrixX3f& C) {
    std::vector<float> values(C.size());
    for (Eigen::Index i = 0; i < C.rows(); ++i)
      for (int c = 0; c < 3; ++c) values[3 * i + c] = C(i, c);
    return accessor(values, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, C.rows(), TINYGLTF_TARGET_ARRAY_BUFFER);
  }

 private:
  tinygltf::Model& model_;
};

/// The weights of a mesh with one morph target per frame after the first, keyed so that frame f shows target f - 1
/// alone (frames x (frames - 1) values).
std::vector<float> frameMorphWeights(int frames) {
  std::vector<float> morph(static_cast<size_t>(frames) * (frames - 1), 0.0f);
  for (int f = 1; f < frames; ++f) morph[static_cast<size_t>(f) * (frames - 1) + (f - 1)] = 1.0f;
  return morph;
}

/// Key times of `frames` frames at `fps`, as an animation sampler's input accessor.
int frameTimes(GltfWriter& writer, tinygltf::Model& model, int frames, double fps) {
  std::vector<float> times(frames);
  for (int f = 0; f < frames; ++f) times[f] = static_cast<float>(f / fps);
  const int input = writer.floats(times, TINYGLTF_TYPE_SCALAR, frames);
  model.accessors[input].minValues = {times.front()};
  model.accessors[input].maxValues = {times.back()};
  return input;
}

std::string glbBytes(tinygltf::Model& model, const std::string& what) {
  model.buffers[0].data.resize((model.buffers[0].data.size() + 3) / 4 * 4, 0);
  std::ostringstream bytes;
  tinygltf::TinyGLTF gltf;
  PIXELCLOTH_CHECK(gltf.WriteGltfSceneToStream(&model, bytes, false, true), what << ": writing the GLB failed");
  return bytes.str();
}

std::vector<float> quaternion(const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  return {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()), static_cast<float>(q.w())};
}

}  // namespace

void writeAnimatedGlb(const std::filesystem::path& path, const AnimatedScene& scene) {
  PIXELCLOTH_CHECK(scene.body, path.string() << ": a scene without a body");
  const body::Body& body = *scene.body;
  const body::Skeleton& skeleton = body.skeleton;
  const int frames = static_cast<int>(scene.poses.size());
  PIXELCLOTH_CHECK(frames >= 1 && (!scene.garment || static_cast<int>(scene.garmentFrames.size()) == frames) &&
                       static_cast<int>(scene.rootRotations.size()) == frames &&
                       scene.rootTranslations.rows() == frames,
                   path.string() << ": " << frames << " poses, " << scene.garmentFrames.size() << " garment frames, "
                                 << scene.rootRotations.size() << " root rotations; expected as many of each");
  for (int f = 0; scene.garment && f < frames; ++f)
    PIXELCLOTH_CHECK(
        scene.garmentFrames[f].rows() == scene.garment->numVertices() && scene.garmentFrames[f].allFinite(),
        path.string() << ": garment frame " << f << " has " << scene.garmentFrames[f].rows() << " vertices (expected "
                      << scene.garment->numVertices() << ") or positions that are not finite");
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "pixelcloth";
  GltfWriter writer(model);
  const int J = skeleton.numJoints();

  // The skeleton: one node per joint, at its rest offset from its parent (rest frames are world-aligned).
  for (int j = 0; j < J; ++j) {
    tinygltf::Node node;
    node.name = skeleton.names[j];
    const int parent = skeleton.parents[j];
    const Eigen::RowVector3d offset =
        parent < 0 ? Eigen::RowVector3d(skeleton.positions.row(j))
                   : Eigen::RowVector3d(skeleton.positions.row(j) - skeleton.positions.row(parent));
    node.translation = {offset.x(), offset.y(), offset.z()};
    model.nodes.push_back(node);
  }
  for (int j = 0; j < J; ++j)
    if (skeleton.parents[j] >= 0) model.nodes[skeleton.parents[j]].children.push_back(j);

  // The body: rest positions, its four strongest joints per vertex, the skin.
  const int V = body.mesh.numVertices();
  std::vector<std::uint16_t> joints(4 * static_cast<size_t>(V));
  std::vector<float> weights(4 * static_cast<size_t>(V));
  std::vector<int> order(J);
  for (int v = 0; v < V; ++v) {
    std::iota(order.begin(), order.end(), 0);
    std::partial_sort(order.begin(), order.begin() + std::min(4, J), order.end(),
                      [&](int a, int b) { return body.weights(v, a) > body.weights(v, b); });
    double sum = 0;
    for (int k = 0; k < std::min(4, J); ++k) sum += body.weights(v, order[k]);
    for (int k = 0; k < 4; ++k) {
      joints[4 * v + k] = static_cast<std::uint16_t>(k < J ? order[k] : 0);
      weights[4 * v + k] = k < J && sum > 0 ? static_cast<float>(body.weights(v, order[k]) / sum) : 0.0f;
    }
  }
  tinygltf::Primitive skin;
  skin.mode = TINYGLTF_MODE_TRIANGLES;
  skin.attributes["POSITION"] = writer.positions(body.mesh.V);
  skin.attributes["JOINTS_0"] = writer.accessor(joints, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, V,
                                                TINYGLTF_TARGET_ARRAY_BUFFER);
  skin.attributes["WEIGHTS_0"] =
      writer.accessor(weights, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, V, TINYGLTF_TARGET_ARRAY_BUFFER);
  skin.indices = writer.indices(body.mesh.F, body.mesh.numVertices());
  tinygltf::Mesh bodyMesh;
  bodyMesh.name = "body";
  bodyMesh.primitives.push_back(skin);
  model.meshes.push_back(bodyMesh);
  std::vector<float> inverseBind;
  for (int j = 0; j < J; ++j) {
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    m.topRightCorner<3, 1>() = -skeleton.positions.row(j).transpose().cast<float>();
    inverseBind.insert(inverseBind.end(), m.data(), m.data() + 16);  // column-major, as glTF stores matrices
  }
  tinygltf::Skin skinning;
  skinning.name = "skeleton";
  for (int j = 0; j < J; ++j) skinning.joints.push_back(j);
  const int root = skeleton.index("root");
  skinning.skeleton = root;
  skinning.inverseBindMatrices = writer.floats(inverseBind, TINYGLTF_TYPE_MAT4, J);
  model.skins.push_back(skinning);
  tinygltf::Node bodyNode;
  bodyNode.name = "body";
  bodyNode.mesh = 0;
  bodyNode.skin = 0;
  model.nodes.push_back(bodyNode);

  // The garment: frame 0 and one morph target per later frame (its displacement from frame 0).
  const int bodyNodeIndex = J, garmentNodeIndex = J + 1;
  tinygltf::Scene sceneNodes;
  sceneNodes.nodes = {root, bodyNodeIndex};
  if (scene.garment) {
    const core::Mesh& garment = *scene.garment;
    tinygltf::Primitive cloth;
    cloth.mode = TINYGLTF_MODE_TRIANGLES;
    cloth.attributes["POSITION"] = writer.positions(scene.garmentFrames.front());
    cloth.indices = writer.indices(garment.F, garment.numVertices());
    for (int f = 1; f < frames; ++f)
      cloth.targets.push_back({{"POSITION", writer.positions(scene.garmentFrames[f] - scene.garmentFrames.front())}});
    tinygltf::Mesh garmentMesh;
    garmentMesh.name = "garment";
    garmentMesh.primitives.push_back(cloth);
    garmentMesh.weights.assign(frames - 1, 0.0);
    model.meshes.push_back(garmentMesh);
    tinygltf::Node garmentNode;
    garmentNode.name = "garment";
    garmentNode.mesh = 1;
    model.nodes.push_back(garmentNode);
    sceneNodes.nodes.push_back(garmentNodeIndex);
  }
  model.scenes.push_back(sceneNodes);
  model.defaultScene = 0;

  // The animation, keyed at every frame.
  tinygltf::Animation animation;
  animation.name = "motion";
  const int input = frameTimes(writer, model, frames, scene.fps);
  auto channel = [&](int node, const std::string& pathName, const std::vector<float>& values, int type) {
    tinygltf::AnimationSampler sampler;
    sampler.input = input;
    sampler.output = writer.floats(values, type, type == TINYGLTF_TYPE_SCALAR ? values.size() : frames);
    sampler.interpolation = "LINEAR";
    animation.samplers.push_back(sampler);
    tinygltf::AnimationChannel c;
    c.sampler = static_cast<int>(animation.samplers.size()) - 1;
    c.target_node = node;
    c.target_path = pathName;
    animation.channels.push_back(c);
  };
  const std::array<int, 10> poseJoints = skeleton.poseJointIndices();
  for (int k = 0; k < 10; ++k) {
    std::vector<float> rotations;
    for (int f = 0; f < frames; ++f) {
      const std::vector<float> q = quaternion(scene.poses[f].rotations[k]);
      rotations.insert(rotations.end(), q.begin(), q.end());
    }
    channel(poseJoints[k], "rotation", rotations, TINYGLTF_TYPE_VEC4);
  }
  std::vector<float> rootRotation, rootTranslation;
  for (int f = 0; f < frames; ++f) {
    const std::vector<float> q = quaternion(scene.rootRotations[f]);
    rootRotation.insert(rootRotation.end(), q.begin(), q.end());
    for (int c = 0; c < 3; ++c)
      rootTranslation.push_back(static_cast<float>(skeleton.positions(root, c) + scene.rootTranslations(f, c)));
  }
  channel(root, "rotation", rootRotation, TINYGLTF_TYPE_VEC4);
  channel(root, "translation", rootTranslation, TINYGLTF_TYPE_VEC3);
  if (scene.garment && frames > 1)
    channel(garmentNodeIndex, "weights", frameMorphWeights(frames), TINYGLTF_TYPE_SCALAR);
  model.animations.push_back(animation);
  core::writeTextAtomically(path, glbBytes(model, path.string()));
}

std::string meshesGlb(const std::vector<GlbMesh>& meshes, double fps) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "pixelcloth";
  GltfWriter writer(model);
  tinygltf::Scene sceneNodes;
  tinygltf::Animation animation;
  animation.name = "frames";
  int maxFrames = 1;
  for (const GlbMesh& mesh : meshes) maxFrames = std::max(maxFrames, static_cast<int>(mesh.frames.size()));
  const int input = maxFrames > 1 ? frameTimes(writer, model, maxFrames, fps) : -1;
  for (const GlbMesh& mesh : meshes) {
    const int frames = static_cast<int>(mesh.frames.size());
    PIXELCLOTH_CHECK(frames >= 1, "glb mesh '" << mesh.name << "': no frames");
    const Eigen::Index V = mesh.frames.front().rows();
    for (int f = 0; f < frames; ++f)
      PIXELCLOTH_CHECK(mesh.frames[f].rows() == V && mesh.frames[f].allFinite(),
                       "glb mesh '" << mesh.name << "': frame " << f + 1 << " has " << mesh.frames[f].rows()
                                    << " vertices (expected " << V << ") or positions that are not finite");
    PIXELCLOTH_CHECK(mesh.faces.size() == 0 || (mesh.faces.minCoeff() >= 0 && mesh.faces.maxCoeff() < V),
                     "glb mesh '" << mesh.name << "': a face names a vertex beyond its " << V);
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.attributes["POSITION"] = writer.positions(mesh.frames.front());
    primitive.indices = writer.indices(mesh.faces, V);
    for (const auto& [name, C] : mesh.colors) {
      PIXELCLOTH_CHECK(C.rows() == V && C.allFinite(), "glb mesh '" << mesh.name << "': colours " << name << " for "
                                                                    << C.rows() << " vertices (expected " << V << ")");
      primitive.attributes[name] = writer.colors(C);
    }
    for (int f = 1; f < frames; ++f)
      primitive.targets.push_back({{"POSITION", writer.positions(mesh.frames[f] - mesh.frames.front())}});
    tinygltf::Mesh gltfMesh;
    gltfMesh.name = mesh.name;
    gltfMesh.primitives.push_back(primitive);
    if (frames > 1) gltfMesh.weights.assign(frames - 1, 0.0);
    model.meshes.push_back(gltfMesh);
    tinygltf::Node node;
    node.name = mesh.name;
    node.mesh = static_cast<int>(model.meshes.size()) - 1;
    model.nodes.push_back(node);
    const int nodeIndex = static_cast<int>(model.nodes.size()) - 1;
    sceneNodes.nodes.push_back(nodeIndex);
    if (frames > 1) {
      PIXELCLOTH_CHECK(frames == maxFrames, "glb mesh '" << mesh.name << "': " << frames << " frames, others "
                                                         << maxFrames << " (expected one frame or as many)");
      tinygltf::AnimationSampler sampler;
      sampler.input = input;
      const std::vector<float> weights = frameMorphWeights(frames);
      sampler.output = writer.floats(weights, TINYGLTF_TYPE_SCALAR, weights.size());
      sampler.interpolation = "STEP";
      animation.samplers.push_back(sampler);
      tinygltf::AnimationChannel channel;
      channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
      channel.target_node = nodeIndex;
      channel.target_path = "weights";
      animation.channels.push_back(channel);
    }
  }
  model.scenes.push_back(sceneNodes);
  model.defaultScene = 0;
  if (!animation.channels.empty()) model.animations.push_back(animation);
  return glbBytes(model, "glb");
}

}  // namespace pixelcloth::motion
