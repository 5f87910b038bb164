// pixelcloth body: the built-in mannequin or an imported body, with skeleton, weights and parts.
#include "pixelcloth/body/body.h"

#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/viz/previews.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct BodyArgs {
  std::string out;
  double shape = 0.0;
  std::string corrupt;
  double corruptFraction = 0.5;
  std::string importMesh;
  std::string joints;
  bool largestComponent = false;
};

void runBody(const BodyArgs& args) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  PIXELCLOTH_CHECK(args.importMesh.empty() == args.joints.empty(),
                   "body: --import MESH and --joints JSON go together (a mesh needs its joint positions)");
  PIXELCLOTH_CHECK(!args.importMesh.empty() || !args.largestComponent,
                   "body: --largest-component goes with --import (the built-in mannequin is one piece)");
  PIXELCLOTH_CHECK(args.importMesh.empty() || args.shape == 0.0,
                   "body: --shape changes the built-in mannequin; it cannot be combined with --import");
  Body body;
  std::string description;
  if (args.importMesh.empty()) {
    MannequinOptions options;
    options.shape = args.shape;
    options.validate();
    checkOutputFolder(args.out);
    checkRunFolder(args.out, {"skeleton.json", {}, "a body"});
    PIXELCLOTH_INFO("body: meshing the built-in mannequin (shape " << args.shape << ")");
    body = makeMannequin(options);
    description = "built-in mannequin, shape " + std::to_string(args.shape);
  } else {
    JointPositions joints = readJointPositions(args.joints);
    Mesh mesh = readMesh(args.importMesh);
    checkOutputFolder(args.out);
    checkRunFolder(args.out, {"skeleton.json", {}, "a body"});
    PIXELCLOTH_INFO("body: importing " << args.importMesh << " (" << mesh.numVertices() << " vertices)");
    ImportOptions options;
    options.largestComponent = args.largestComponent;
    body = importBody(mesh, joints, args.importMesh, options);
    description = "imported from " + args.importMesh;
  }
  if (!args.corrupt.empty()) {
    body.weights = corruptUpperArmWeights(body.skeleton, body.weights, args.corrupt, args.corruptFraction);
    body.parts = collisionParts(body);
    description += ", upper-arm weights corrupted (" + args.corrupt + ", " + std::to_string(args.corruptFraction) + ")";
  }
  saveBody(args.out, body, description);
  writePng(std::filesystem::path(args.out) / "body.png", renderBodySheet(body));
  PIXELCLOTH_INFO("body: " << body.mesh.numVertices() << " vertices, " << body.mesh.numFaces() << " faces, "
                           << body.skeleton.numJoints() << " joints -> " << args.out
                           << "/{body.obj, skeleton.json, weights.npy, parts.json, body.png}");
}
}  // namespace

void registerBody(CLI::App& app) {
  auto args = std::make_shared<BodyArgs>();
  CLI::App* verb = app.add_subcommand("body",
                                      "Make the built-in mannequin (or import a body): mesh, skeleton, skin "
                                      "weights, collision parts and a picture");
  verb->add_option("--out", args->out, "Output folder (body.obj, skeleton.json, weights.npy, parts.json, body.png)")
      ->required();
  verb->add_option("--shape", args->shape, "Girth of the built-in mannequin: -1 thinner ... 0 default ... 2 thicker")
      ->capture_default_str()
      ->check(CLI::Range(-1.0, 2.0));
  verb->add_option("--corrupt-weights", args->corrupt,
                   "Reproduce the paper's skinning artifacts: move upper-arm weight to the torso ('torso') or to the "
                   "torso and the opposite arm ('torso+arm')")
      ->check(CLI::IsMember({"torso", "torso+arm"}));
  verb->add_option("--corrupt-fraction", args->corruptFraction, "Fraction of the upper-arm weight that is moved")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  verb->add_option("--import", args->importMesh, "Closed body mesh (OBJ/PLY/OFF) standing in a T- or A-pose");
  verb->add_option("--joints", args->joints,
                   "JSON of joint positions for --import: {\"joints\": {\"lower_back\": [x, y, z], ...}} with the 10 "
                   "pose joints (root, head, l_hand, r_hand optional)");
  verb->add_flag("--largest-component", args->largestComponent,
                 "With --import: keep only the mesh's largest piece, dropping separate shells (eyes, teeth, "
                 "accessories); without it a mesh of several pieces is refused");
  verb->callback([args] { runBody(*args); });
}

}  // namespace pixelcloth::apps
