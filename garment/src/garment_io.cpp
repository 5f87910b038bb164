// Garment folders: garment.obj + garment.json, and the garment's traits in it.
#include <algorithm>
#include <cmath>

#include "garment_checks.h"
#include "garment_traits.h"
#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

using namespace core;

void GarmentTraits::validate(int numVertices, const std::string& context) const {
  PIXELCLOTH_CHECK(poseJoints >= 1 && poseJoints <= static_cast<int>(body::kPoseJoints.size()),
                   context << ": " << poseJoints << " pose joints, expected 1 to " << body::kPoseJoints.size());
  for (size_t i = 0; i < pinned.size(); ++i)
    PIXELCLOTH_CHECK(pinned[i] >= 0 && pinned[i] < numVertices,
                     context << ": pinned[" << i << "] is vertex " << pinned[i] << ", expected 0.." << numVertices - 1
                             << " (a row of the garment's " << numVertices << " vertices)");
  PIXELCLOTH_CHECK(imageWidth >= 8 && imageWidth <= 4096 && imageHeight >= 8 && imageHeight <= 4096,
                   context << ": image size " << imageWidth << " x " << imageHeight << ", expected 8 to 4096 each");
  PIXELCLOTH_CHECK(std::isfinite(normalLossWeight) && normalLossWeight >= 0 && normalLossWeight <= 100,
                   context << ": normal loss weight " << normalLossWeight << ", expected 0 to 100");
  PIXELCLOTH_CHECK(std::isfinite(edgeLossWeight) && edgeLossWeight >= 0 && edgeLossWeight <= 100,
                   context << ": edge loss weight " << edgeLossWeight << ", expected 0 to 100");
}

nlohmann::json GarmentTraits::toJson() const {
  std::vector<std::string> joints(body::kPoseJoints.begin(), body::kPoseJoints.begin() + poseJoints);
  return {{"pose_joints", joints},
          {"pinned", pinned},
          {"image_size", {imageWidth, imageHeight}},
          {"offset_frame", rootFrameOffsets ? "root" : "local"},
          {"normal_loss_weight", normalLossWeight},
          {"edge_loss_weight", edgeLossWeight}};
}

GarmentTraits GarmentTraits::fromJson(const nlohmann::json& json, int numVertices, const std::string& context) {
  PIXELCLOTH_CHECK(json.is_object(), context << ": expected a JSON object, found " << json.type_name());
  GarmentTraits traits;
  if (json.contains("pose_joints")) {
    const auto joints = requireValue<std::vector<std::string>>(json, "pose_joints", context);
    std::string order;
    for (const std::string& name : body::kPoseJoints) order += (order.empty() ? "" : ", ") + name;
    PIXELCLOTH_CHECK(!joints.empty() && joints.size() <= body::kPoseJoints.size() &&
                         std::equal(joints.begin(), joints.end(), body::kPoseJoints.begin()),
                     context << ": pose_joints must be the first joints of the pose vector, in its order (" << order
                             << "), e.g. the first 4 for a garment the arms do not move");
    traits.poseJoints = static_cast<int>(joints.size());
  }
  if (json.contains("pinned")) traits.pinned = requireValue<std::vector<int>>(json, "pinned", context);
  if (json.contains("image_size")) {
    const auto size = requireValue<std::vector<int>>(json, "image_size", context);
    PIXELCLOTH_CHECK(size.size() == 2, context << ": image_size has " << size.size() << " entries, expected [w, h]");
    traits.imageWidth = size[0];
    traits.imageHeight = size[1];
  }
  if (json.contains("offset_frame")) {
    const auto frame = requireValue<std::string>(json, "offset_frame", context);
    PIXELCLOTH_CHECK(frame == "local" || frame == "root",
                     context << ": offset_frame is '" << frame << "', expected local or root");
    traits.rootFrameOffsets = frame == "root";
  }
  if (json.contains("normal_loss_weight"))
    traits.normalLossWeight = requireValue<double>(json, "normal_loss_weight", context);
  if (json.contains("edge_loss_weight")) traits.edgeLossWeight = requireValue<double>(json, "edge_loss_weight", context);
  traits.validate(numVertices, context);
  return traits;
}

GarmentTraits traitsOfGarmentJson(const nlohmann::json& root, const core::Mesh& mesh, const std::string& file) {
  if (root.contains("traits")) return GarmentTraits::fromJson(root["traits"], mesh.numVertices(), file + ": traits");
  const auto name = root.contains("name") && root["name"].is_string() ? root["name"].get<std::string>() : "";
  return legacyTemplateTraits(name, mesh);
}

nlohmann::json garmentJson(const Garment& garment) {
  nlohmann::json seams = nlohmann::json::array();
  for (const Seam& seam : garment.seams)
    seams.push_back({{"name", seam.name}, {"vertices", seam.vertices}, {"joins_layouts", seam.joinsLayouts}});
  nlohmann::json openings = nlohmann::json::array();
  for (const Opening& opening : garment.openings)
    openings.push_back({{"name", opening.name}, {"vertices", opening.vertices}});
  nlohmann::json lines = nlohmann::json::array();
  for (const CageLine& line : garment.lines)
    lines.push_back({{"name", line.name},
                     {"kind", curveKindName(line.kind)},
                     {"closed", line.closed},
                     {"vertices", line.vertices}});
  nlohmann::json layouts = nlohmann::json::array();
  for (int l = 0; l < garment.numLayouts(); ++l) {
    Eigen::AlignedBox2d box = garment.layoutBounds(l);
    layouts.push_back(
        {{"name", garment.layouts[l]}, {"bounds_m", {box.min().x(), box.min().y(), box.max().x(), box.max().y()}}});
  }
  nlohmann::json json = {
      {"format", "pixelcloth.garment"},
      {"version", 1},
      {"name", garment.name},
      {"mesh", {{"file", "garment.obj"}, {"vertices", garment.mesh.numVertices()}, {"faces", garment.mesh.numFaces()}}},
      {"units", "metres; UVs are pattern-space metres per layout"},
      {"layouts", layouts},
      {"panels", garment.panels},
      {"face_layout",
       std::vector<int>(garment.faceLayout.data(), garment.faceLayout.data() + garment.faceLayout.size())},
      {"face_panel", std::vector<int>(garment.facePanel.data(), garment.facePanel.data() + garment.facePanel.size())},
      {"seams", seams},
      {"openings", openings},
      {"cage_lines", lines},
      {"traits", garment.traits.toJson()},
      {"meshing", garment.meshing.summary(garment.mesh.numVertices())}};
  if (!garment.recipe.is_null()) json["template"] = garment.recipe;
  return json;
}

void saveGarment(const std::filesystem::path& folder, const Garment& garment) {
  garment.mesh.validate(garment.name);
  garment.traits.validate(garment.mesh.numVertices(), garment.name + ": traits");
  const nlohmann::json json = garmentJson(garment);
  writeMesh(folder / "garment.obj", garment.mesh);
  writeJson(folder / "garment.json", json);
}

Garment loadGarment(const std::filesystem::path& folder) {
  Garment garment = importGarment(folder / "garment.obj", folder / "garment.json");
  const nlohmann::json root = readJson(folder / "garment.json");
  if (!root.contains("template")) return garment;
  // A template's folder: its OBJ holds the mesh to 9 digits; the recipe rebuilds it exactly (the mesher is
  // deterministic), as long as the OBJ still is that mesh. An edited OBJ is the user's garment: the file wins.
  const Garment rebuilt = rebuildTemplate(root["template"], (folder / "garment.json").string() + ": template");
  const core::Mesh& read = garment.mesh;
  bool same = rebuilt.mesh.F == read.F && rebuilt.mesh.V.rows() == read.V.rows() &&
              (rebuilt.mesh.V - read.V).cwiseAbs().maxCoeff() < 1e-6 && rebuilt.faceLayout == garment.faceLayout;
  for (int f = 0; same && f < read.numFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      same = same && (rebuilt.mesh.UV.row(rebuilt.mesh.FUV(f, k)) - read.UV.row(read.FUV(f, k))).norm() < 1e-6;
  if (!same) {
    garment.recipe = nullptr;
    return garment;
  }
  garment.mesh = rebuilt.mesh;
  garment.vertexUV = rebuilt.vertexUV;
  garment.meshing = rebuilt.meshing;
  garment.recipe = rebuilt.recipe;
  return garment;
}

}  // namespace pixelcloth::garment
