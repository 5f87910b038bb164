// pixelcloth dress: dress a garment (template or folder) on a body (cage morph, push-out, relaxation, embedding).
#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct DressArgs {
  std::string garment = "tshirt";
  std::string body;
  std::string out;
};

void runDress(const DressArgs& args) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  checkOutputFolder(args.out);
  pixelcloth::core::checkRunFolder(args.out, {"dressing.json", {}, "a dressing"});
  const Garment garment = resolveGarment(args.garment, "--garment");  // before the body: a bad garment fails fast
  Body body;
  if (args.body.empty()) {
    PIXELCLOTH_INFO("dress: meshing the built-in mannequin");
    body = makeMannequin();
  } else {
    body = loadBody(args.body);
  }
  const cage::Cage bodyCage = cage::bodyCage(body);
  const cage::Cage garmentCage = cage::garmentCage(garment);
  const auto start = std::chrono::steady_clock::now();
  const cage::Dressing dressing = cage::dressGarment(body, bodyCage, garment, garmentCage);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  PIXELCLOTH_INFO("dress: " << garment.name << " (" << garment.mesh.numVertices() << " vertices) on a "
                            << body.mesh.numVertices() << "-vertex body in " << 1e3 * seconds
                            << " ms: " << dressing.summary());
  if (!dressing.relaxConverged)
    PIXELCLOTH_WARN("dress: the relaxation stopped at its cap of " << dressing.relaxIterations
                                                                   << " sweeps with vertices still moving "
                                                                   << 1000 * dressing.relaxResidual
                                                                   << " mm a sweep; the dressing may be uneven");
  if (const std::string advice = cage::fitAdvice(dressing); !advice.empty()) PIXELCLOTH_WARN("dress: " << advice);
  viz::writeDressingFolder(body, garment, dressing, args.out);
}
}  // namespace

void registerDress(CLI::App& app) {
  auto args = std::make_shared<DressArgs>();
  CLI::App* verb = app.add_subcommand(
      "dress", "Dress a garment on a body: cage morph, push-out, edge-length relaxation on the body, embedding");
  verb->add_option("--garment", args->garment, kGarmentHelp)->capture_default_str();
  verb->add_option("--body", args->body, "Body folder written by 'pixelcloth body' (default: the built-in mannequin)");
  verb->add_option("--out", args->out,
                   "Output folder: dressed.obj (dressed positions with the pattern UVs), area_distortion.png, "
                   "dressed.png, dressing.json (iterations, residual, area ratios before / after, penetration)")
      ->required();
  verb->callback([args] { runDress(*args); });
}

}  // namespace pixelcloth::apps
