// pixelcloth dress: dress a garment template on a body (cage morph, push-out, relaxation, embedding).
#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/body/body.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/core/mesh_index.h"
#include "pixelcloth/viz/pictures.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct DressArgs {
  std::string garment = "tshirt";
  std::string body;
  std::string out;
};

/// min, max and the 5 / 50 / 95 percentiles of the face area ratios (3D over pattern area).
nlohmann::json ratioStats(const Eigen::VectorXd& ratios) {
  std::vector<double> values(ratios.data(), ratios.data() + ratios.size());
  std::sort(values.begin(), values.end());
  auto at = [&](double q) { return values.empty() ? 0.0 : values[std::lround(q * (values.size() - 1))]; };
  return {{"min", at(0)}, {"p5", at(0.05)}, {"median", at(0.5)}, {"p95", at(0.95)}, {"max", at(1)}};
}

void runDress(const DressArgs& args) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  checkOutputFolder(args.out);
  Body body;
  if (args.body.empty()) {
    PIXELCLOTH_INFO("dress: meshing the built-in mannequin");
    body = makeMannequin();
  } else {
    body = loadBody(args.body);
  }
  const Garment garment = args.garment == "tshirt" ? makeTShirt() : makeNecktie();
  const cage::Cage bodyCage = cage::bodyCage(body);
  const cage::Cage garmentCage = cage::garmentCage(garment);
  const auto start = std::chrono::steady_clock::now();
  const cage::Dressing dressing = cage::dressGarment(body, bodyCage, garment, garmentCage);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  PIXELCLOTH_INFO("dress: " << garment.name << " (" << garment.mesh.numVertices() << " vertices) on a "
                            << body.mesh.numVertices() << "-vertex body in " << 1e3 * seconds
                            << " ms: " << dressing.summary());
  writeDressingFolder(body, garment, dressing, args.out);
}
}  // namespace

void writeDressingFolder(const body::Body& body, const garment::Garment& garment, const cage::Dressing& dressing,
                         const std::filesystem::path& out) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  PIXELCLOTH_CHECK(
      dressing.relaxed.rows() == garment.mesh.numVertices(),
      "dress: the dressing has " << dressing.relaxed.rows() << " vertices, the garment " << garment.mesh.numVertices());
  Garment dressed = garment;
  dressed.mesh.V = dressing.relaxed;
  writeMesh(out / "dressed.obj", dressed.mesh);
  writePng(out / "area_distortion.png", viz::renderAreaDistortion(garment, dressing));
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
                                    {"relax_residual_m", dressing.relaxResidual},
                                    {"area_ratio_before", ratioStats(dressing.areaRatioBefore)},
                                    {"area_ratio_after", ratioStats(dressing.areaRatioAfter)},
                                    {"vertices_per_part", parts}});
  PIXELCLOTH_INFO("dress: -> " << out.string() << "/{dressed.obj, area_distortion.png, dressed.png, dressing.json}");
}

void registerDress(CLI::App& app) {
  auto args = std::make_shared<DressArgs>();
  CLI::App* verb = app.add_subcommand(
      "dress", "Dress a garment on a body: cage morph, push-out, edge-length relaxation on the body, embedding");
  verb->add_option("--garment", args->garment, "Which garment: tshirt or necktie")
      ->check(CLI::IsMember({"tshirt", "necktie"}))
      ->capture_default_str();
  verb->add_option("--body", args->body, "Body folder written by 'pixelcloth body' (default: the built-in mannequin)");
  verb->add_option("--out", args->out,
                   "Output folder: dressed.obj (dressed positions with the pattern UVs), area_distortion.png, "
                   "dressed.png, dressing.json (iterations, residual, area ratios before / after, penetration)")
      ->required();
  verb->callback([args] { runDress(*args); });
}

}  // namespace pixelcloth::apps
