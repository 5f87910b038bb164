// The output folders of the cage, dress and dataset stats verbs (the demo's too): files, figures and their pictures.
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh_index.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/viz/patch_picture.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"

namespace pixelcloth::viz {

using namespace core;
using garment::Garment;

namespace {
/// min, max and the 5 / 50 / 95 percentiles of the face area ratios (3D over pattern area).
nlohmann::json ratioStats(const Eigen::VectorXd& ratios) {
  std::vector<double> values(ratios.data(), ratios.data() + ratios.size());
  std::sort(values.begin(), values.end());
  auto at = [&](double q) { return values.empty() ? 0.0 : values[std::lround(q * (values.size() - 1))]; };
  return {{"min", at(0)}, {"p5", at(0.05)}, {"median", at(0.5)}, {"p95", at(0.95)}, {"max", at(1)}};
}

}  // namespace

void writeCageFolder(const garment::Garment& garment, const std::filesystem::path& out, int size) {
  const cage::Cage cage = cage::garmentCage(garment);
  const std::vector<patches::Patch> patchList = patches::segmentPatches(garment, cage::cutEdges(cage));

  nlohmann::json cageJson = cage::toJson(cage);
  cageJson["garment"] = garment.name;
  core::writeJson(out / "cage.json", cageJson);

  nlohmann::json list = nlohmann::json::array();
  double largest = 0;
  for (const patches::Patch& patch : patchList) {
    const Eigen::Vector2d extent = patches::patchPixelExtent(garment, patch, size);
    largest = std::max(largest, extent.maxCoeff());
    list.push_back({{"id", patch.id},
                    {"side", garment.layouts[patch.layout]},
                    {"vertices", patch.vertices},
                    {"boundary", patch.boundary},
                    {"bbox_px_" + std::to_string(size), {extent.x(), extent.y()}}});
  }
  core::writeJson(out / "patches.json", {{"garment", garment.name}, {"image_size", size}, {"patches", list}});

  std::vector<PictureCurve> curves;
  for (const cage::CageCurve& curve : cage.curves) curves.push_back({curve.vertices, curve.closed, curve.kind});
  core::writePng(out / "cage.png", renderPatches(garment, patchList, curves, size));
  PIXELCLOTH_INFO("cage: " << garment.name << ": " << cage.curves.size() << " curves, " << cage.nodes.size()
                           << " nodes, " << patchList.size() << " patches, largest patch " << largest << " px of "
                           << size << " -> " << out.string() << "/{cage.json, patches.json, cage.png}");
}

void writeDressingFolder(const body::Body& body, const garment::Garment& garment, const cage::Dressing& dressing,
                         const std::filesystem::path& out) {
  PIXELCLOTH_CHECK(
      dressing.relaxed.rows() == garment.mesh.numVertices(),
      "dress: the dressing has " << dressing.relaxed.rows() << " vertices, the garment " << garment.mesh.numVertices());
  Garment dressed = garment;
  dressed.mesh.V = dressing.relaxed;
  writeMesh(out / "dressed.obj", dressed.mesh);
  writePng(out / "area_distortion.png", renderAreaDistortion(garment, dressing));
  writePng(out / "dressed.png", renderGarmentOnBody(dressed, &body));

  const std::vector<bool> inside = insideClosedMesh(body.mesh.V, body.mesh.F, dressing.relaxed);
  const long insideAfter = std::count(inside.begin(), inside.end(), true);
  std::vector<int> partCounts(body.parts.size(), 0);
  for (int p : dressing.part) {
    if (p >= 0 && p < static_cast<int>(partCounts.size())) ++partCounts[p];
  }
  nlohmann::json parts = nlohmann::json::object();
  for (size_t p = 0; p < body.parts.size(); ++p) parts[body.parts[p].name] = partCounts[p];
  writeJson(out / "dressing.json", {{"garment", garment.name},
                                    {"garment_vertices", garment.mesh.numVertices()},
                                    {"body_vertices", body.mesh.numVertices()},
                                    {"cage_vertices", dressing.cageVertices.size()},
                                    {"pushed_vertices", dressing.pushedVertices},
                                    {"max_penetration_m", dressing.maxPenetration},
                                    {"inside_after_relaxation", insideAfter},
                                    {"relax_iterations", dressing.relaxIterations},
                                    {"relax_converged", dressing.relaxConverged},
                                    {"relax_residual_m", dressing.relaxResidual},
                                    {"area_ratio_before", ratioStats(dressing.areaRatioBefore)},
                                    {"area_ratio_after", ratioStats(dressing.areaRatioAfter)},
                                    {"vertices_per_part", parts}});
  PIXELCLOTH_INFO("dress: -> " << out.string() << "/{dressed.obj, area_distortion.png, dressed.png, dressing.json}");
}

void writeFaceStatistics(const garment::Garment& garment, const data::FaceStatistics& stats,
                         const std::filesystem::path& source, const std::filesystem::path& out) {
  const std::string over = " over " + std::to_string(stats.samples) + " samples";
  writePng(out / "area_distortion.png", renderFacePanels(garment,
                                                         {{"smallest area ratio" + over, stats.minAreaRatio},
                                                          {"largest area ratio" + over, stats.maxAreaRatio}},
                                                         FaceScale::AreaRatio));
  writePng(out / "self_intersection.png",
           renderFacePanels(garment, {{"faces through the garment itself" + over, stats.selfIntersection}},
                            FaceScale::Fraction));
  const auto list = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  writeJson(out / "face_statistics.json", {{"dataset", source.string()},
                                           {"samples", stats.samples},
                                           {"faces", garment.mesh.numFaces()},
                                           {"samples_self_intersecting", stats.samplesSelfIntersecting},
                                           {"min_area_ratio", list(stats.minAreaRatio)},
                                           {"max_area_ratio", list(stats.maxAreaRatio)},
                                           {"self_intersection_fraction", list(stats.selfIntersection)}});
}

}  // namespace pixelcloth::viz
