// pixelcloth demo: everything that exists, end to end, on the built-in body and garments, as a report folder of
// pictures (index.html, report.json). The sections are viz/'s; this verb runs them in the order of the data flow.
#include "pixelcloth/viz/demo.h"

#include <memory>

#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct DemoArgs {
  std::string out;
  viz::DemoOptions options;
};

void runDemo(const DemoArgs& args) {
  const viz::DemoOptions& demo = args.options;
  viz::Report report(args.out);
  const body::Body body = viz::demoBody(report);
  viz::demoBodyCage(report, body);
  viz::demoShapes(report, body);
  viz::demoSkinningArtifacts(report, body);
  viz::demoPoses(report, body, demo);
  viz::demoBodyImport(report, body);
  viz::demoGarments(report, body);
  viz::demoCageAndPatches(report);
  viz::demoBases(report);
  viz::demoClothImages(report);
  viz::demoDressing(report, body);
  viz::demoTShirtDataset(report, body, demo);
  viz::demoReconstruction(report, body);
  viz::demoOwnGarment(report, body, demo);
  viz::demoNecktieDataset(report, body, demo);
  viz::demoPoseSampling(report, body, demo);
  viz::demoNetworks(report);
  viz::demoLearning(report, body, demo);
  viz::demoSeams(report, body, demo);
  report.write();
}
}  // namespace

void registerDemo(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* verb = app.add_subcommand("demo",
                                      "Run everything that exists on the built-in body and garments; write "
                                      "a report folder with pictures");
  verb->add_option("--out", args->out, "Report folder (index.html, report.json, pictures, meshes)")->required();
  verb->add_option("--poses", args->options.poses, "Number of random poses to show")
      ->capture_default_str()
      ->check(CLI::Range(1, 200));
  verb->add_option("--filter-poses", args->options.filterPoses,
                   "Poses drawn and simulated on the T-shirt for the filtering histograms")
      ->capture_default_str()
      ->check(CLI::Range(2, 2000));
  verb->add_option("--tshirt-samples", args->options.tshirtSamples,
                   "Simulated T-shirt samples (80% train the spline's length model, 10% test the reconstruction)")
      ->capture_default_str()
      ->check(CLI::Range(1, 2000));
  verb->add_option("--own-garment-samples", args->options.ownGarmentSamples,
                   "Simulated samples of the imported T-shirt OBJ (the own-garment section)")
      ->capture_default_str()
      ->check(CLI::Range(1, 2000));
  verb->add_option("--learning-epochs", args->options.learningEpochs, "Epochs of each learned model")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  verb->add_option("--seed", args->options.seed, "Seed of the random poses")->capture_default_str();
  verb->callback([args] { runDemo(*args); });
}

}  // namespace pixelcloth::apps
