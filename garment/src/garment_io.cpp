// Garment folders: garment.obj + garment.json.
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

using namespace core;

void saveGarment(const std::filesystem::path& folder, const Garment& garment) {
  garment.mesh.validate(garment.name);
  nlohmann::json seams = nlohmann::json::array();
  for (const Seam& seam : garment.seams)
    seams.push_back({{"name", seam.name}, {"vertices", seam.vertices}, {"joins_layouts", seam.joinsLayouts}});
  nlohmann::json openings = nlohmann::json::array();
  for (const Opening& opening : garment.openings)
    openings.push_back({{"name", opening.name}, {"vertices", opening.vertices}});
  nlohmann::json lines = nlohmann::json::array();
  for (const CageLine& line : garment.lines)
    lines.push_back({{"name", line.name}, {"kind", line.kind}, {"closed", line.closed}, {"vertices", line.vertices}});
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
      {"meshing", garment.meshing.summary(garment.mesh.numVertices())}};
  writeMesh(folder / "garment.obj", garment.mesh);
  writeJson(folder / "garment.json", json);
}

}  // namespace pixelcloth::garment
