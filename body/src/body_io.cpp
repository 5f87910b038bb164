// Body folders: body.obj, skeleton.json, weights.npy, parts.json.
#include <algorithm>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/npy.h"

namespace pixelcloth::body {

using namespace core;

namespace fs = std::filesystem;

namespace {

nlohmann::json toJson(const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

Eigen::Vector3d vectorField(const nlohmann::json& object, const std::string& key, const std::string& context) {
  const nlohmann::json& value = requireField(object, key, context);
  PIXELCLOTH_CHECK(value.is_array() && value.size() == 3 &&
                       std::all_of(value.begin(), value.end(), [](const nlohmann::json& x) { return x.is_number(); }),
                   context << ": field '" << key << "' must be [x, y, z]");
  Eigen::Vector3d v(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
  PIXELCLOTH_CHECK(v.allFinite(), context << ": field '" << key << "' is not finite");
  return v;
}

}  // namespace

void saveBody(const fs::path& folder, const Body& body, const std::string& description) {
  body.validate("body");
  const Skeleton& s = body.skeleton;
  nlohmann::json joints = nlohmann::json::array();
  for (int j = 0; j < s.numJoints(); ++j) {
    nlohmann::json joint = {
        {"name", s.names[j]},
        {"parent", s.parents[j] < 0 ? nlohmann::json(nullptr) : nlohmann::json(s.names[s.parents[j]])},
        {"position", toJson(s.positions.row(j).transpose())},
        {"bone_end", toJson(s.boneEnds.row(j).transpose())}};
    bool posable = std::find(kPoseJoints.begin(), kPoseJoints.end(), s.names[j]) != kPoseJoints.end();
    joint["posable"] = posable;
    if (posable) {
      const JointLimits& limits = jointLimits(s.names[j]);
      joint["limits_deg"] = {
          {"lower", toJson(limits.lower)}, {"upper", toJson(limits.upper)}, {"source", limits.source}};
    }
    joints.push_back(joint);
  }
  nlohmann::json skeleton = {
      {"format", "pixelcloth.skeleton"},
      {"version", 1},
      {"description", description},
      {"units", "metres; Y up, body faces +Z, the wearer's left on +X; rest T-pose"},
      {"pose_joints", std::vector<std::string>(kPoseJoints.begin(), kPoseJoints.end())},
      {"pose_vector", "10 row-major 3x3 local rotations relative to the rest pose, in pose_joints order (90 floats)"},
      {"euler_order", "limits are Euler angles in degrees (x, y, z) composed x, then z, then y: R = Ry Rz Rx"},
      {"joints", joints},
      {"weights", {{"file", "weights.npy"}, {"shape", {body.mesh.numVertices(), s.numJoints()}}, {"columns", s.names}}},
      {"mesh", {{"file", "body.obj"}, {"vertices", body.mesh.numVertices()}, {"faces", body.mesh.numFaces()}}}};
  nlohmann::json parts = nlohmann::json::array();
  for (const BodyPart& part : body.parts)
    parts.push_back({{"name", part.name}, {"faces", part.faces}, {"vertices", part.vertices}});

  Mesh mesh = body.mesh;
  mesh.UV.resize(0, 2);
  mesh.FUV.resize(0, 3);
  writeMesh(folder / "body.obj", mesh);
  writeJson(folder / "skeleton.json", skeleton);
  writeNpy(folder / "weights.npy", Eigen::MatrixXf(body.weights.cast<float>()));
  writeJson(folder / "parts.json", {{"format", "pixelcloth.parts"}, {"version", 1}, {"parts", parts}});
}

Body loadBody(const fs::path& folder) {
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_directory(folder, ec), folder.string() << ": no such body folder (expected body.obj, "
                                                                    "skeleton.json, weights.npy, parts.json; "
                                                                    "make one with 'pixelcloth body --out DIR')");
  // A dataset or dressing folder holds its body in body/: say so rather than "body.obj: no such file".
  PIXELCLOTH_CHECK(fs::exists(folder / "body.obj", ec) || !fs::is_regular_file(folder / "body" / "body.obj", ec),
                   folder.string() << ": is not a body folder but holds one (a dataset or dressing folder?); give its "
                                      "body folder, "
                                   << (folder / "body").string());
  Body body;
  body.mesh = readMesh(folder / "body.obj");

  fs::path skeletonPath = folder / "skeleton.json";
  std::string context = skeletonPath.string();
  nlohmann::json skeleton = readJson(skeletonPath);
  const nlohmann::json& joints = requireField(skeleton, "joints", context);
  PIXELCLOTH_CHECK(joints.is_array() && !joints.empty(), context << ": 'joints' must be a non-empty array");
  Skeleton& s = body.skeleton;
  const int n = static_cast<int>(joints.size());
  s.positions.resize(n, 3);
  s.boneEnds.resize(n, 3);
  for (int j = 0; j < n; ++j) {
    std::string jointContext = context + ": joint " + std::to_string(j);
    s.names.push_back(requireValue<std::string>(joints[j], "name", jointContext));
    s.positions.row(j) = vectorField(joints[j], "position", jointContext).transpose();
    s.boneEnds.row(j) = vectorField(joints[j], "bone_end", jointContext).transpose();
  }
  for (int j = 0; j < n; ++j) {
    const nlohmann::json& parent = requireField(joints[j], "parent", context + ": joint '" + s.names[j] + "'");
    if (parent.is_null()) {
      s.parents.push_back(-1);
    } else {
      PIXELCLOTH_CHECK(parent.is_string(), context << ": joint '" << s.names[j] << "': parent must be a name or null");
      auto it = std::find(s.names.begin(), s.names.end(), parent.get<std::string>());
      PIXELCLOTH_CHECK(it != s.names.end(), context << ": joint '" << s.names[j] << "' has unknown parent '"
                                                    << parent.get<std::string>() << "'");
      s.parents.push_back(static_cast<int>(it - s.names.begin()));
    }
  }
  s.validate(context);

  body.weights = readNpyMatrixF(folder / "weights.npy", body.mesh.numVertices(), s.numJoints()).cast<double>();

  fs::path partsPath = folder / "parts.json";
  nlohmann::json parts = readJson(partsPath);
  const nlohmann::json& list = requireField(parts, "parts", partsPath.string());
  PIXELCLOTH_CHECK(list.is_array(), partsPath.string() << ": 'parts' must be an array");
  for (const nlohmann::json& item : list) {
    BodyPart part;
    part.name = requireValue<std::string>(item, "name", partsPath.string());
    part.faces = requireValue<std::vector<int>>(item, "faces", partsPath.string() + ": part '" + part.name + "'");
    part.vertices = requireValue<std::vector<int>>(item, "vertices", partsPath.string() + ": part '" + part.name + "'");
    body.parts.push_back(std::move(part));
  }
  body.validate(folder.string());
  return body;
}

}  // namespace pixelcloth::body
