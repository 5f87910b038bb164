#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/body/skeleton.h"

namespace pixelcloth::body {

/// Reads a pose from JSON, in either form:
///   {"pose": [90 numbers]}  (10 row-major 3x3 local rotations, DESIGN.md order), or
///   {"joints": {"l_arm": {"euler_deg": [x, y, z]}, "neck": {"rotation": [9 numbers]}, ...}}
/// Joints left out stay at rest. Unknown joints, wrong counts, non-finite numbers and matrices that
/// are not rotations are refused with the file and joint named.
/// Joint angles beyond their limits (jointLimits(), Euler angles as Pose::toEulerDegrees gives them) are refused,
/// the joint, angle and limit named, or with BeyondLimits::Clamp (the CLI's --clamp-to-limits) clamped with a warning.
enum class BeyondLimits { Refuse, Clamp };
Pose readPose(const std::filesystem::path& path, BeyondLimits beyondLimits = BeyondLimits::Refuse);

/// Reads every pose of a file: one pose object as readPose takes, a list of them, or {"poses": [...]} as
/// `pixelcloth pose` writes its poses.json. Each is checked as readPose checks one, its index named.
std::vector<Pose> readPoses(const std::filesystem::path& path, BeyondLimits beyondLimits = BeyondLimits::Refuse);

/// Parses the same forms from an already-read JSON value; `context` names its origin in messages.
Pose poseFromJson(const nlohmann::json& json, const std::string& context);

/// {"pose": [90], "euler_deg": {"l_arm": [x, y, z], ...}}: readable by readPose and by people.
nlohmann::json poseToJson(const Pose& pose);

}  // namespace pixelcloth::body
