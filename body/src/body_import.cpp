// Importing a user's body: closed mesh + joint positions -> skeleton, bone-heat weights, T-pose.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh_index.h"

namespace pixelcloth::body {

using namespace core;

namespace {

const std::vector<std::string>& optionalJointNames() {
  static const std::vector<std::string> names = {"root", "head", "l_hand", "r_hand"};
  return names;
}

std::string vectorText(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

/// Smallest rotation taking unit vector a onto unit vector b.
Eigen::Matrix3d rotationBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return Eigen::Quaterniond::FromTwoVectors(a, b).toRotationMatrix();
}

/// The mesh point furthest along `direction` from `origin`, among vertices within `radius` of the ray.
Eigen::Vector3d extremeAlong(const Eigen::MatrixX3d& V, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                             double radius) {
  Eigen::Vector3d best = origin;
  double bestT = 0;
  for (int i = 0; i < V.rows(); ++i) {
    Eigen::Vector3d d = V.row(i).transpose() - origin;
    double t = d.dot(direction);
    if (t > bestT && (d - t * direction).norm() < radius) {
      bestT = t;
      best = origin + t * direction;
    }
  }
  return best;
}

/// The units a body of `height` (in the file's units) seems to be in, as advice for a message; "" when none fits.
std::string unitsAdvice(double height) {
  const std::pair<double, const char*> units[] = {
      {0.01, "centimetres: scale it by 0.01"}, {0.001, "millimetres: scale it by 0.001"},
      {0.0254, "inches: scale it by 0.0254"}, {0.3048, "feet: scale it by 0.3048"}};
  for (const auto& [metres, advice] : units)
    if (height * metres >= 1.0 && height * metres <= 2.3) return std::string("; it looks like ") + advice;
  return "";
}

/// Pose joints closer than this (metres) are refused as one point.
constexpr double kMinJointSpacing = 0.005;

}  // namespace

JointPositions readJointPositions(const std::filesystem::path& path) {
  nlohmann::json json = readJson(path);
  PIXELCLOTH_CHECK(json.is_object(), path.string() << ": expected a JSON object of joint positions");
  const nlohmann::json& joints = json.contains("joints") ? json["joints"] : json;
  PIXELCLOTH_CHECK(joints.is_object(), path.string() << ": 'joints' must be an object {name: [x, y, z]}");
  std::vector<std::string> known(kPoseJoints.begin(), kPoseJoints.end());
  known.insert(known.end(), optionalJointNames().begin(), optionalJointNames().end());
  JointPositions positions;
  for (const auto& [name, value] : joints.items()) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      PIXELCLOTH_FAIL(path.string() << ": unknown joint '" << name << "'; expected names: " << list);
    }
    PIXELCLOTH_CHECK(
        value.is_array() && value.size() == 3 && value[0].is_number() && value[1].is_number() && value[2].is_number(),
        path.string() << ": joint '" << name << "' must be [x, y, z] in metres");
    Eigen::Vector3d p(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
    PIXELCLOTH_CHECK(p.allFinite(), path.string() << ": joint '" << name << "' has a non-finite coordinate");
    positions[name] = p;
  }
  for (const auto& name : kPoseJoints) {
    PIXELCLOTH_CHECK(positions.count(name), path.string() << ": missing joint '" << name
                                                          << "' (required: the 10 "
                                                             "pose joints lower_back, spine, spine1, neck, l_shoulder, "
                                                             "l_arm, l_forearm, r_shoulder, r_arm, r_forearm)");
  }
  // Joints on top of each other (a file of zeros, or one position pasted for all) leave bones without a direction.
  for (size_t a = 0; a < kPoseJoints.size(); ++a)
    for (size_t b = a + 1; b < kPoseJoints.size(); ++b) {
      const double apart = (positions.at(kPoseJoints[a]) - positions.at(kPoseJoints[b])).norm();
      PIXELCLOTH_CHECK(apart >= kMinJointSpacing,
                       path.string() << ": joints '" << kPoseJoints[a] << "' and '" << kPoseJoints[b] << "' are "
                                     << apart * 1000
                                     << " mm apart; expected each pose joint at its own place, at least "
                                     << kMinJointSpacing * 1000 << " mm from the others (positions in metres)");
    }
  return positions;
}

Body importBody(const Mesh& input, const JointPositions& joints, const std::string& context,
                const ImportOptions& options) {
  input.validate(context);
  // Metres: a person is 0.5 to 2.5 m tall, whichever axis is up.
  const double height = (input.V.colwise().maxCoeff() - input.V.colwise().minCoeff()).maxCoeff();
  PIXELCLOTH_CHECK(height >= 0.5 && height <= 2.5, context << ": the body is " << height
                                                           << " units tall (its bounding box's largest side); "
                                                              "expected 0.5 to 2.5 metres"
                                                           << unitsAdvice(height));
  TopologyReport topology = checkTopology(input.numVertices(), input.F);
  const std::string shells = "separate shells such as eyes, teeth or accessories; --largest-component keeps the "
                             "largest and drops the others";
  auto componentText = [&](int c) {
    return "component " + std::to_string(c) + " of " + std::to_string(topology.components) + " (" +
           std::to_string(topology.componentFaces[c - 1]) + " faces; the largest has " +
           std::to_string(topology.componentFaces[0]) + ")";
  };
  Mesh mesh = input;
  if (topology.components > 1 && options.largestComponent) {
    mesh = largestComponent(input);
    PIXELCLOTH_WARN(context << ": kept the largest of " << topology.components << " components ("
                            << topology.componentFaces[0] << " of " << input.numFaces() << " faces, "
                            << mesh.numVertices() << " of " << input.numVertices()
                            << " vertices); vertex numbers below count in the kept mesh");
    topology = checkTopology(mesh.numVertices(), mesh.F);
  }
  PIXELCLOTH_CHECK(topology.closedManifold(),
                   context << ": the body mesh must be closed and manifold, but " << topology.firstProblem
                           << (topology.components > 1 ? ", on " + componentText(topology.firstProblemComponent) : "")
                           << " (" << topology.boundaryEdges << " boundary edges, " << topology.nonManifoldEdges
                           << " non-manifold edges, " << topology.nonManifoldVertices << " non-manifold vertices, "
                           << topology.inconsistentEdges << " inconsistently oriented edges)"
                           << (topology.components > 1 && topology.firstProblemComponent > 1 ? "; " + shells : ""));
  PIXELCLOTH_CHECK(topology.components == 1, context << ": the body mesh is closed but has " << topology.components
                                                     << " components (face counts: largest "
                                                     << topology.componentFaces[0] << ", next "
                                                     << topology.componentFaces[1] << "); expected one body: "
                                                     << shells);
  if (enclosedVolume(mesh.V, mesh.F) < 0) mesh.F.col(1).swap(mesh.F.col(2));
  for (const auto& name : kPoseJoints)
    PIXELCLOTH_CHECK(joints.count(name), context << ": missing joint '" << name << "'");

  // Fit the standard skeleton: given joints, optional ones estimated from the mesh.
  Skeleton s;
  s.names = standardJointNames();
  s.parents = standardJointParents();
  s.positions.resize(s.numJoints(), 3);
  auto get = [&](const std::string& name) { return joints.at(name); };
  Eigen::Vector3d up = (get("neck") - get("lower_back")).normalized();
  for (int j = 0; j < s.numJoints(); ++j) {
    const std::string& name = s.names[j];
    if (joints.count(name)) {
      s.positions.row(j) = joints.at(name).transpose();
    } else if (name == "root") {
      s.positions.row(j) = (get("lower_back") - 0.6 * (get("spine") - get("lower_back"))).transpose();
    } else if (name == "head") {
      Eigen::Vector3d top = extremeAlong(mesh.V, get("neck"), up, 0.12);
      s.positions.row(j) = (get("neck") + 0.45 * (top - get("neck"))).transpose();
    }
  }
  Eigen::Vector3d headTop = extremeAlong(mesh.V, s.positions.row(s.index("head")).transpose(), up, 0.1);
  auto handTip = [&](const std::string& side) -> Eigen::Vector3d {
    if (joints.count(side + "_hand")) return joints.at(side + "_hand");
    Eigen::Vector3d elbow = get(side + "_forearm");
    Eigen::Vector3d direction = (elbow - get(side + "_arm")).normalized();
    return extremeAlong(mesh.V, elbow, direction, 0.12);
  };
  Eigen::Vector3d tips[2] = {handTip("l"), handTip("r")};
  s.boneEnds.resize(s.numJoints(), 3);
  for (int j = 0; j < s.numJoints(); ++j) {
    const std::string& name = s.names[j];
    Eigen::Vector3d end;
    if (name == "head")
      end = headTop - 0.02 * up;
    else if (name == "l_forearm")
      end = tips[0];
    else if (name == "r_forearm")
      end = tips[1];
    else if (name == "root")
      end = s.positions.row(s.index("lower_back"));
    else if (name == "lower_back")
      end = s.positions.row(s.index("spine"));
    else if (name == "spine")
      end = s.positions.row(s.index("spine1"));
    else if (name == "spine1")
      end = s.positions.row(s.index("neck"));
    else if (name == "neck")
      end = s.positions.row(s.index("head"));
    else if (name == "l_shoulder")
      end = s.positions.row(s.index("l_arm"));
    else if (name == "l_arm")
      end = s.positions.row(s.index("l_forearm"));
    else if (name == "r_shoulder")
      end = s.positions.row(s.index("r_arm"));
    else
      end = s.positions.row(s.index("r_forearm"));
    s.boneEnds.row(j) = end.transpose();
  }
  s.validate(context);

  // Every joint must lie inside the body.
  std::vector<bool> inside = insideClosedMesh(mesh.V, mesh.F, s.positions);
  for (int j = 0; j < s.numJoints(); ++j) {
    PIXELCLOTH_CHECK(inside[j], context << ": joint '" << s.names[j] << "' at "
                                        << vectorText(s.positions.row(j).transpose())
                                        << " lies outside the body mesh; joints must be inside the body");
  }
  PIXELCLOTH_CHECK(s.positions(s.index("l_arm"), 0) > s.positions(s.index("r_arm"), 0),
                   context << ": l_arm is not on the +x side of r_arm; the body must face +z with y up (the wearer's "
                              "left on +x)");

  Body body;
  body.mesh = mesh;
  body.skeleton = s;
  body.weights = boneHeatWeights(mesh.V, mesh.F, s);

  // Bring the arms to the T-pose: rotate each upper arm, then each forearm, onto the horizontal.
  Pose pose = Pose::identity();
  bool moved = false;
  for (const auto& [side, sign] :
       {std::pair<std::string, double>{"l", 1.0}, std::pair<std::string, double>{"r", -1.0}}) {
    Eigen::Vector3d target(sign, 0, 0);
    Eigen::Vector3d shoulderToElbow = (get(side + "_forearm") - get(side + "_arm")).normalized();
    Eigen::Vector3d elbowToHand = (tips[side == "l" ? 0 : 1] - get(side + "_forearm")).normalized();
    Eigen::Matrix3d armRotation = rotationBetween(shoulderToElbow, target);
    Eigen::Matrix3d foreGlobal = rotationBetween(armRotation * elbowToHand, target);
    double angle = std::acos(std::clamp(shoulderToElbow.dot(target), -1.0, 1.0)) * 180.0 / M_PI;
    if (angle < 2.0 && std::acos(std::clamp((armRotation * elbowToHand).dot(target), -1.0, 1.0)) < 2.0 * M_PI / 180)
      continue;
    auto poseIndex = [&](const std::string& name) {
      return static_cast<int>(std::find(kPoseJoints.begin(), kPoseJoints.end(), name) - kPoseJoints.begin());
    };
    pose.rotations[poseIndex(side + "_arm")] = armRotation;
    pose.rotations[poseIndex(side + "_forearm")] = armRotation.transpose() * foreGlobal * armRotation;
    moved = true;
    PIXELCLOTH_INFO(context << ": " << side << " arm was " << std::lround(angle) << " degrees from horizontal; "
                            << "rotated into the T-pose");
  }
  if (moved) {
    JointTransforms transforms = forwardKinematics(s, pose);
    body.mesh.V = skin(s, mesh.V, body.weights, pose);
    Skeleton posed = s;
    posed.positions = transforms.positions;
    for (int j = 0; j < s.numJoints(); ++j) {
      posed.boneEnds.row(j) = (transforms.rotations[j] * (s.boneEnds.row(j) - s.positions.row(j)).transpose() +
                               transforms.positions.row(j).transpose())
                                  .transpose();
    }
    body.skeleton = posed;
  }
  body.parts = collisionParts(body);
  return body;
}

}  // namespace pixelcloth::body
