// pixelcloth model: a network's size (the paper's decoders and the fully connected baselines) without training it.
#include "pixelcloth/learn/model.h"

#include <iostream>
#include <memory>

#include "pixelcloth/core/error.h"
#include "pixelcloth/garment/garment.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct ModelArgs {
  std::string architecture;
  learn::ModelSpec spec;
  std::string garment = "tshirt";
  bool summary = false;
};

void runModel(ModelArgs args) {
  PIXELCLOTH_CHECK(args.summary, "model: nothing to do; --summary prints the model's size as JSON");
  args.spec.architecture = learn::architectureFromName(args.architecture, "--arch");
  const bool baseline = args.spec.architecture == learn::Architecture::FullyConnected ||
                        args.spec.architecture == learn::Architecture::FullyConnectedPca;
  if (baseline && args.spec.outputValues == 0)
    args.spec.outputValues = 3 * garment::resolveGarment(args.garment, "--garment").mesh.numVertices();
  std::cout << learn::summarize(args.spec).toJson().dump() << std::endl;
}
}  // namespace

void registerModel(CLI::App& app) {
  auto args = std::make_shared<ModelArgs>();
  CLI::App* verb = app.add_subcommand(
      "model", "Describe a network: the whole-garment, patch or necktie decoder, or a fully connected baseline");
  verb->add_option("--arch", args->architecture, "Network: whole, patch, necktie, fc or fc-pca")
      ->required()
      ->check(CLI::IsMember({"whole", "patch", "necktie", "fc", "fc-pca"}));
  verb->add_option("--width", args->spec.width, "Multiplier of every channel count (e.g. 0.25 for CPU runs), (0, 4]")
      ->capture_default_str();
  verb->add_option("--min-channels", args->spec.minChannels,
                   "Decoders: channels an upsampling layer keeps at the least, whatever the width; 0: the plain "
                   "multiplier")
      ->capture_default_str();
  verb->add_option("--inputs", args->spec.inputSize,
                   "Floats in (pose plus marker features); 0: the pose alone (90, the necktie 36)")
      ->capture_default_str();
  verb->add_option("--garment", args->garment,
                   std::string("fc, fc-pca: whose vertices (3 values each) they predict. ") + kGarmentHelp)
      ->capture_default_str();
  verb->add_option("--values", args->spec.outputValues, "fc, fc-pca: values out instead of the garment's 3 x #V")
      ->capture_default_str();
  verb->add_option("--components", args->spec.pcaComponents, "fc-pca: PCA coefficients decoded through the basis")
      ->capture_default_str();
  verb->add_flag(
      "--summary", args->summary,
      "Print one JSON object: architecture, width, min_channels, parameters, input, output, gflop_forward, layers");
  verb->callback([args] { runModel(*args); });
}

}  // namespace pixelcloth::apps
