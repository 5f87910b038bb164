#include "pixelcloth/body/pose_io.h"

#include <algorithm>
#include <cstdio>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"

namespace pixelcloth::body {

using namespace core;

namespace {
Eigen::VectorXf numbers(const nlohmann::json& value, int count, const std::string& context) {
  PIXELCLOTH_CHECK(value.is_array() && static_cast<int>(value.size()) == count,
                   context << ": expected an array of " << count << " numbers, found "
                           << (value.is_array() ? std::to_string(value.size()) + " entries" : value.type_name()));
  Eigen::VectorXf out(count);
  for (int i = 0; i < count; ++i) {
    PIXELCLOTH_CHECK(value[i].is_number(),
                     context << ": entry " << i << " is " << value[i].type_name() << ", expected a number");
    out[i] = value[i].get<float>();
  }
  return out;
}
}  // namespace

Pose poseFromJson(const nlohmann::json& json, const std::string& context) {
  PIXELCLOTH_CHECK(json.is_object(), context << ": expected a JSON object with 'pose' or 'joints'");
  if (json.contains("pose")) return Pose::fromVector(numbers(json["pose"], kPoseSize, context + ": pose"), context);
  PIXELCLOTH_CHECK(json.contains("joints"), context << ": expected a field 'pose' (90 numbers) or 'joints' "
                                                       "({name: {\"euler_deg\": [x, y, z]}})");
  const nlohmann::json& joints = json["joints"];
  PIXELCLOTH_CHECK(joints.is_object(), context << ": 'joints' must be an object keyed by joint name");
  Eigen::VectorXf vector = Pose::identity().toVector();
  for (const auto& [name, value] : joints.items()) {
    auto it = std::find(kPoseJoints.begin(), kPoseJoints.end(), name);
    if (it == kPoseJoints.end()) {
      std::string list;
      for (const auto& n : kPoseJoints) list += (list.empty() ? "" : ", ") + n;
      PIXELCLOTH_FAIL(context << ": unknown joint '" << name << "'; posable joints are " << list);
    }
    int k = static_cast<int>(it - kPoseJoints.begin());
    std::string jointContext = context + ": joint '" + name + "'";
    PIXELCLOTH_CHECK(value.is_object() && (value.contains("euler_deg") || value.contains("rotation")),
                     jointContext << ": expected {\"euler_deg\": [x, y, z]} or {\"rotation\": [9 numbers]}");
    Eigen::Matrix3d rotation;
    if (value.contains("euler_deg")) {
      Eigen::VectorXf degrees = numbers(value["euler_deg"], 3, jointContext + ": euler_deg");
      PIXELCLOTH_CHECK(degrees.allFinite(), jointContext << ": euler_deg is not finite");
      rotation = rotationFromEulerXZY(degrees.cast<double>());
    } else {
      Eigen::VectorXf m = numbers(value["rotation"], 9, jointContext + ": rotation");
      rotation = Eigen::Map<const Eigen::Matrix<float, 3, 3, Eigen::RowMajor>>(m.data()).cast<double>();
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) vector[9 * k + 3 * i + j] = static_cast<float>(rotation(i, j));
  }
  return Pose::fromVector(vector, context);
}

namespace {
/// `pose` within the joint limits: as it is, clamped, or refused naming `context`.
Pose withinLimits(const Pose& pose, BeyondLimits beyondLimits, const std::string& context) {
  const std::string beyond = pose.limitViolation();
  if (beyond.empty()) return pose;
  PIXELCLOTH_CHECK(beyondLimits == BeyondLimits::Clamp,
                   context << ": " << beyond << "; --clamp-to-limits clamps every angle into its limits instead");
  PIXELCLOTH_WARN(context << ": " << beyond << "; clamped into the limits (--clamp-to-limits)");
  return pose.clampedToLimits();
}
}  // namespace

Pose readPose(const std::filesystem::path& path, BeyondLimits beyondLimits) {
  const nlohmann::json json = readJson(path);
  if (json.is_object() && json.contains("poses") && !json.contains("pose") && !json.contains("joints")) {
    const nlohmann::json& list = json["poses"];
    PIXELCLOTH_CHECK(list.is_array() && list.size() == 1,
                     path.string() << ": holds " << (list.is_array() ? list.size() : 0)
                                   << " poses where one is expected (`pixelcloth pose --pose` takes them all)");
    return withinLimits(poseFromJson(list[0], path.string() + ": pose 0"), beyondLimits, path.string() + ": pose 0");
  }
  return withinLimits(poseFromJson(json, path.string()), beyondLimits, path.string());
}

std::vector<Pose> readPoses(const std::filesystem::path& path, BeyondLimits beyondLimits) {
  const nlohmann::json json = readJson(path);
  const nlohmann::json* list = &json;
  if (json.is_object() && json.contains("poses") && !json.contains("pose") && !json.contains("joints"))
    list = &json["poses"];
  if (!list->is_array()) return {withinLimits(poseFromJson(json, path.string()), beyondLimits, path.string())};
  PIXELCLOTH_CHECK(!list->empty(), path.string() << ": an empty list of poses");
  std::vector<Pose> poses;
  for (size_t i = 0; i < list->size(); ++i) {
    const std::string context = path.string() + ": pose " + std::to_string(i);
    poses.push_back(withinLimits(poseFromJson((*list)[i], context), beyondLimits, context));
  }
  return poses;
}

nlohmann::json poseToJson(const Pose& pose) {
  Eigen::VectorXf vector = pose.toVector();
  Eigen::Matrix<double, 10, 3> degrees = pose.toEulerDegrees();
  nlohmann::json euler = nlohmann::json::object();
  for (int k = 0; k < 10; ++k) euler[kPoseJoints[k]] = {degrees(k, 0), degrees(k, 1), degrees(k, 2)};
  return {{"pose", std::vector<float>(vector.data(), vector.data() + vector.size())}, {"euler_deg", euler}};
}

}  // namespace pixelcloth::body
