// The viewer's static site: scenes as GLB files and their script twins, the page, and three.js beside it.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unordered_set>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/edge_key.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/motion/glb.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/stitch/seams.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/render.h"
#include "pixelcloth/viz/viewer.h"

namespace pixelcloth::viz {

namespace assets {
// viewer/index.html and viewer/viewer.js, embedded by viz/CMakeLists.txt.
extern const char* const kViewerHtml;
extern const char* const kViewerJs;
}  // namespace assets

namespace {
namespace fs = std::filesystem;

const std::array<const char*, 3> kThreeFiles = {"build/three.min.js", "examples/js/loaders/GLTFLoader.js",
                                                "examples/js/controls/OrbitControls.js"};

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    std::uint32_t word = 0;
    for (size_t k = 0; k < 3; ++k) word = (word << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? digits[(word >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

Eigen::MatrixX3f uniformColor(Eigen::Index rows, const Eigen::Vector3f& rgb) {
  Eigen::MatrixX3f C(rows, 3);
  C.rowwise() = rgb.transpose();
  return C;
}

Eigen::MatrixX3f rampColors(const Eigen::VectorXd& values, double scale, bool diverging = false) {
  Eigen::MatrixX3f C(values.size(), 3);
  for (Eigen::Index i = 0; i < values.size(); ++i)
    C.row(i) = colorRamp(std::clamp(values(i) / scale, 0.0, 1.0), diverging).cast<float>().transpose();
  return C;
}

nlohmann::json rgb(const Eigen::Vector3d& c) { return {c.x(), c.y(), c.z()}; }

/// Segments of a curve's vertex chain: consecutive vertices that share a mesh edge (a closed curve's last and first
/// included), as pairs of garment vertices.
std::vector<int> curveSegments(const ViewCurve& curve, const std::unordered_set<std::uint64_t>& edges) {
  std::vector<int> segments;
  const size_t n = curve.vertices.size();
  for (size_t k = 0; n > 1 && k < n; ++k) {
    const int a = curve.vertices[k], b = curve.vertices[(k + 1) % n];
    if (a != b && edges.count(core::edgeKey(a, b))) segments.insert(segments.end(), {a, b});
  }
  return segments;
}

/// One scene's GLB and the description the page reads beside it.
std::pair<std::string, nlohmann::json> sceneFiles(const ViewScene& scene, const std::string& what) {
  PIXELCLOTH_CHECK(!scene.garments.empty(), what << ": a scene without a garment");
  const int frames = static_cast<int>(scene.garments.front().frames.size());
  std::vector<motion::GlbMesh> meshes;
  nlohmann::json meta = {{"name", scene.name}, {"frames", frames}, {"fps", scene.fps}, {"info", scene.info}};
  if (!scene.bodyFrames.empty()) {
    meshes.push_back({"body", scene.bodyFaces, scene.bodyFrames, {}});  // one colour, the page's
    meta["body"] = {{"node", "body"}, {"vertices", scene.bodyFrames.front().rows()}};
  }
  meta["garments"] = nlohmann::json::array();
  for (size_t g = 0; g < scene.garments.size(); ++g) {
    const ViewGarment& garment = scene.garments[g];
    const std::string node = "garment_" + std::to_string(g);
    motion::GlbMesh mesh{node, scene.garmentFaces, garment.frames, {}};
    const Eigen::Index V = garment.frames.front().rows();
    mesh.colors["COLOR_0"] =
        uniformColor(V, garment.truth ? Eigen::Vector3f(0.55f, 0.78f, 0.55f) : Eigen::Vector3f(0.45f, 0.62f, 0.88f));
    const bool hasError = garment.errorCm.size() > 0;
    if (hasError) {
      PIXELCLOTH_CHECK(garment.errorCm.size() == V, what << ": " << garment.errorCm.size() << " errors for " << V
                                                         << " vertices of " << garment.name);
      mesh.colors["_ERROR"] = rampColors(garment.errorCm, kViewErrorScaleCm);
    }
    if (scene.patchOfVertex.size() == V) {
      Eigen::MatrixX3f C(V, 3);
      for (Eigen::Index v = 0; v < V; ++v) {
        const core::Color c = paletteColor(scene.patchOfVertex(v));
        C.row(v) << c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f;
      }
      mesh.colors["_PATCH"] = C;
    }
    meshes.push_back(std::move(mesh));
    nlohmann::json entry = {
        {"name", garment.name}, {"node", node}, {"truth", garment.truth}, {"vertices", V}, {"error", hasError}};
    if (hasError) entry["mean_error_cm"] = garment.errorCm.mean();
    meta["garments"].push_back(entry);
  }
  meta["patches"] = scene.patchOfVertex.size() > 0 ? scene.patchOfVertex.maxCoeff() + 1 : 0;
  std::unordered_set<std::uint64_t> edges;
  for (Eigen::Index f = 0; f < scene.garmentFaces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      edges.insert(core::edgeKey(scene.garmentFaces(f, c), scene.garmentFaces(f, (c + 1) % 3)));
  meta["curve_measure"] = scene.curveMeasure;
  meta["curves"] = nlohmann::json::array();
  for (const ViewCurve& curve : scene.curves) {
    const double t = std::isfinite(curve.normalJumpDeg) ? curve.normalJumpDeg / kViewCurveScaleDeg : 0.0;
    meta["curves"].push_back(
        {{"name", curve.name},
         {"segments", curveSegments(curve, edges)},
         {"value", std::isfinite(curve.normalJumpDeg) ? nlohmann::json(curve.normalJumpDeg) : nlohmann::json()},
         {"color", rgb(colorRamp(std::clamp(t, 0.0, 1.0)))}});
  }
  meta["markers"] = nlohmann::json::array();
  for (const Eigen::MatrixX3d& frame : scene.markers) {
    nlohmann::json points = nlohmann::json::array();
    for (Eigen::Index m = 0; m < frame.rows(); ++m)
      points.push_back(frame.row(m).allFinite() ? rgb(frame.row(m).transpose()) : nlohmann::json());
    meta["markers"].push_back(points);
  }
  return {motion::meshesGlb(meshes, scene.fps), meta};
}

}  // namespace

std::vector<ViewCurve> viewCurves(const garment::Garment& garment, const Eigen::MatrixX3d& shown,
                                  const Eigen::MatrixX3d* truth) {
  const stitch::SeamLayout layout(garment);
  const Eigen::MatrixX3d normals = core::faceNormals(shown, garment.mesh.F);
  const Eigen::MatrixX3d truthNormals = truth ? core::faceNormals(*truth, garment.mesh.F) : Eigen::MatrixX3d();
  std::vector<ViewCurve> curves;
  for (const stitch::SeamCurve& seam : layout.curves()) {
    ViewCurve curve{seam.name, seam.vertices, std::nan("")};
    double sum = 0;
    for (const std::array<int, 2>& pair : seam.facePairs) {
      const double fold = stitch::foldAngleDeg(normals, pair);
      sum += truth ? std::abs(fold - stitch::foldAngleDeg(truthNormals, pair)) : fold;
    }
    if (!seam.facePairs.empty()) curve.normalJumpDeg = sum / seam.facePairs.size();
    curves.push_back(std::move(curve));
  }
  // Loops and centre lines run in order along the garment's cage lines; take their chains from there.
  for (const garment::CageLine& line : garment.lines)
    for (ViewCurve& curve : curves)
      if (curve.name == line.name) {
        curve.vertices = line.vertices;
        if (line.closed && !line.vertices.empty()) curve.vertices.push_back(line.vertices.front());
      }
  return curves;
}

Eigen::VectorXi patchOfVertex(const garment::Garment& garment) {
  Eigen::VectorXi patch = Eigen::VectorXi::Constant(garment.mesh.numVertices(), 0);
  std::vector<patches::Patch> list = patches::garmentPatches(garment);
  for (auto it = list.rbegin(); it != list.rend(); ++it)
    for (int v : it->vertices) patch(v) = it->id;
  return patch;
}

fs::path threeJsFolder() {
  const char* env = std::getenv("PIXELCLOTH_THREE_DIR");
  const fs::path folder = env && *env ? fs::path(env) : fs::path("/usr/share/javascript/three");
  for (const char* file : kThreeFiles)
    PIXELCLOTH_CHECK(
        fs::is_regular_file(folder / file),
        "view: three.js is missing: " << (folder / file).string()
                                      << " not found (Debian's libjs-three, which ./scripts/setup installs; "
                                         "or set PIXELCLOTH_THREE_DIR to a folder holding build/ and "
                                         "examples/js/ of three.js r111)");
  return folder;
}

void writeViewSite(const fs::path& out, const ViewSite& site) {
  PIXELCLOTH_CHECK(!site.scenes.empty(), "view: " << site.source << " has nothing to show");
  const fs::path three = threeJsFolder();
  core::ensureOutputFolder(out);
  nlohmann::json list = nlohmann::json::array();
  core::Progress progress("view scenes", static_cast<std::int64_t>(site.scenes.size()));
  for (size_t s = 0; s < site.scenes.size(); ++s) {
    const ViewScene& scene = site.scenes[s];
    char stem[32];
    std::snprintf(stem, sizeof(stem), "scenes/%03zu", s);
    auto [glb, meta] = sceneFiles(scene, site.source + ", scene '" + scene.name + "'");
    core::writeTextAtomically(out / (std::string(stem) + ".glb"), glb);
    core::writeTextAtomically(
        out / (std::string(stem) + ".glb.js"),
        "pixelclothView.sceneLoaded(" + std::to_string(s) + ", \"" + base64(glb) + "\", " + meta.dump() + ");\n");
    list.push_back({{"name", scene.name},
                    {"group", scene.group},
                    {"script", std::string(stem) + ".glb.js"},
                    {"glb", std::string(stem) + ".glb"},
                    {"frames", meta["frames"]},
                    {"garments", meta["garments"].size()},
                    {"body", meta.contains("body")}});
    progress.advance(1);
  }
  progress.finish();
  nlohmann::json ramp = nlohmann::json::array();
  for (int k = 0; k <= 10; ++k) ramp.push_back(rgb(colorRamp(k / 10.0)));
  const nlohmann::json description = {{"title", site.title},
                                      {"source", site.source},
                                      {"scenes", list},
                                      {"ramp", ramp},
                                      {"error_scale_cm", kViewErrorScaleCm},
                                      {"curve_scale_deg", kViewCurveScaleDeg}};
  core::writeTextAtomically(out / "site.js", "var PIXELCLOTH_SITE = " + description.dump(1) + ";\n");
  core::writeTextAtomically(out / "viewer.js", assets::kViewerJs);
  core::writeTextAtomically(out / "index.html", assets::kViewerHtml);
  for (const char* file : kThreeFiles)
    core::writeTextAtomically(out / "three" / fs::path(file).filename(), core::readTextFile(three / file));
}

}  // namespace pixelcloth::viz
