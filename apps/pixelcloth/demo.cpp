// pixelcloth demo: everything that exists, end to end, on the built-in body and garments, as a report folder of
// pictures (index.html, report.json). What simulates, trains or measures is eval/demo.h's, the pictures and sections
// viz/'s; this verb sequences them in the order of the data flow.
#include "pixelcloth/eval/demo.h"

#include <memory>

#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/viz/demo.h"
#include "pixelcloth/viz/viewer.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct DemoArgs {
  std::string out;
  eval::DemoPlan plan;
};

void runDemo(const DemoArgs& args) {
  const eval::DemoPlan& plan = args.plan;
  pixelcloth::core::checkRunFolder(args.out, {"report.json", {{"format", "pixelcloth.demo"}}, "a demo report"});
  viz::Report report(args.out);
  const std::filesystem::path out = report.folder();
  const body::Body body = viz::demoBody(report);
  viz::demoBodyCage(report, body);
  viz::demoShapes(report, body);
  viz::demoSkinningArtifacts(report, body);
  viz::demoPoses(report, body, plan.poses, plan.seed);
  viz::demoBodyImport(report, body);
  viz::demoGarments(report, body);
  viz::demoCageAndPatches(report);
  viz::demoBases(report);
  viz::demoClothImages(report);
  std::vector<eval::DressedGarment> dressed;
  report.step("dressing: T-shirt and necktie on the mannequin", [&] { dressed = eval::dressTemplates(body); });
  viz::demoDressing(report, body, dressed);

  eval::SimulatedDataset tshirt, necktie;
  report.step("datasets: simulated T-shirt samples, checked", [&] {
    tshirt = eval::simulateDataset(out / "dataset_tshirt", out / "body", "tshirt", plan.tshirtSamples, plan.seed);
  });
  viz::demoTShirtDataset(report, body, tshirt);
  eval::EquilibriumDemo equilibrium;
  report.step("static equilibrium: the first T-shirt poses run to equilibrium by the Newton solver", [&] {
    equilibrium = eval::runEquilibriumDemo(out / "dataset_tshirt_newton", out / "body", tshirt.folder, plan);
  });
  viz::demoEquilibrium(report, body, equilibrium);
  eval::DemoReconstruction reconstruction;
  report.step("reconstruction from markers: the T-shirt samples rebuilt by every method",
              [&] { reconstruction = eval::reconstructDemoDataset(out / "dataset_tshirt", out / "reconstruction"); });
  viz::demoReconstruction(report, body, reconstruction);
  eval::OwnGarment own;
  report.step("your own garment: another program's T-shirt OBJ through the pipeline",
              [&] { own = eval::runOwnGarment(out / "own_garment", body, out / "body", plan); });
  viz::demoOwnGarment(report, body, own);
  report.step("datasets: simulated necktie samples, checked", [&] {
    necktie = eval::simulateDataset(out / "dataset_necktie", out / "body", "necktie", plan.necktieSamples, plan.seed);
  });
  viz::demoNecktieDataset(report, body, necktie);
  eval::PoseFiltering filtering;
  report.step("pose sampling: draws pruned and simulated on the T-shirt",
              [&] { filtering = eval::filterSampledPoses(body, plan.filterPoses, plan.seed); });
  viz::demoPoseSampling(report, filtering);
  learn::TrainReport necktieModel;
  report.step("training: a quarter-width necktie decoder on the demo's necktie samples",
              [&] { necktieModel = eval::trainNecktie(out / "dataset_necktie", out / "model_necktie", plan); });
  viz::demoNetworks(report, necktieModel);
  eval::DemoLearning learning;
  report.step("learning: the marker bases, a whole-garment, a patch and a residual patch model trained and measured",
              [&] { learning = eval::runDemoLearning(out, plan); });
  viz::demoLearning(report, body, learning);
  eval::DemoSeams seams;
  report.step("seams: the paper's tables, a GAN blender, every stitch mode measured",
              [&] { seams = eval::runDemoSeams(out, plan); });
  viz::demoSeams(report, body, seams);
  eval::DemoMotion motion;
  report.step("motion: a clip of the demo's own out as a GLB, in through assimp, through the patch decoders",
              [&] { motion = eval::runDemoMotion(out, plan); });
  viz::demoMotion(report, body, motion);
  viz::ViewSite site;
  report.step("viewer: the garments, learned predictions, reconstructions and sequences as a 3D page", [&] {
    site = viz::viewFolder(out);
    viz::writeViewSite(out / "view", site);
  });
  viz::demoViewer(report, site);
  report.write();
}
}  // namespace

void registerDemo(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* verb = app.add_subcommand("demo",
                                      "Run everything that exists on the built-in body and garments; write "
                                      "a report folder with pictures");
  verb->add_option("--out", args->out, "Report folder (index.html, report.json, pictures, meshes)")->required();
  verb->add_option("--poses", args->plan.poses, "Number of random poses to show")
      ->capture_default_str()
      ->check(CLI::Range(1, 200));
  verb->add_option("--filter-poses", args->plan.filterPoses,
                   "Poses drawn and simulated on the T-shirt for the filtering histograms")
      ->capture_default_str()
      ->check(CLI::Range(2, 2000));
  verb->add_option("--tshirt-samples", args->plan.tshirtSamples,
                   "Simulated T-shirt samples (80% train the spline's length model, 10% test the reconstruction)")
      ->capture_default_str()
      ->check(CLI::Range(1, 2000));
  verb->add_option("--own-garment-samples", args->plan.ownGarmentSamples,
                   "Simulated samples of the imported T-shirt OBJ (the own-garment section)")
      ->capture_default_str()
      ->check(CLI::Range(1, 2000));
  verb->add_option("--equilibrium-samples", args->plan.equilibriumSamples,
                   "The T-shirt dataset's first poses run to static equilibrium by the Newton solver")
      ->capture_default_str()
      ->check(CLI::Range(1, 2000));
  verb->add_option("--learning-epochs", args->plan.learningEpochs, "Epochs of each learned model")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  verb->add_option("--seed", args->plan.seed, "Seed of the random poses")->capture_default_str();
  verb->callback([args] { runDemo(*args); });
}

}  // namespace pixelcloth::apps
