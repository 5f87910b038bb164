// pixelcloth train: a decoder or baseline learned from a dataset (the whole garment, the 28 patches, the necktie, or
// the fully connected baselines), in plain or residual mode; or the GAN blender of a trained patch model.
#include "pixelcloth/learn/train.h"

#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/stitch/gan.h"
#include "pixelcloth/viz/pictures.h"
#include "prediction_inputs.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct TrainArgs {
  std::string dataset, out, model = "whole", patches = "all", space, residual, patchModel, loss = "l1",
                            targetScaling = "none", schedule = "constant";
  bool quiet = false;
  learn::TrainOptions options;
  stitch::GanOptions gan;
};

/// "all" -> {}; "3,7,12" -> {3, 7, 12}.
std::vector<int> parsePatchList(const std::string& text) {
  std::vector<int> ids;
  if (text == "all") return ids;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    int id = -1;
    try {
      id = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    PIXELCLOTH_CHECK(used == item.size() && id >= 0,
                     "--patches '" << text << "': expected all or patch ids separated by commas, e.g. 3,7");
    ids.push_back(id);
  }
  PIXELCLOTH_CHECK(!ids.empty(), "--patches '" << text << "': no patch ids");
  return ids;
}

/// --model gan: the blender of the patch model in --patch-model, on --dataset loaded as that model sees it. The shared
/// options apply where given (count > 0), else the blender's defaults; the decoders' own are refused.
void runTrainGan(TrainArgs args, const CLI::App& verb) {
  PIXELCLOTH_CHECK(!args.patchModel.empty(),
                   "train --model gan: give the patch model to blend with --patch-model DIR (pixelcloth train --model "
                   "patch --out DIR)");
  for (const char* option :
       {"--patches", "--components", "--space", "--residual", "--loss", "--target-scaling", "--min-channels",
        "--normal-weight", "--edge-weight", "--networks-at-once", "--schedule", "--patience", "--train-samples"})
    PIXELCLOTH_CHECK(verb.count(option) == 0, "train --model gan: " << option << " is not an option of the blender "
                                                                    << "(it takes the space and base of --patch-model)");
  stitch::GanOptions& gan = args.gan;
  if (verb.count("--width") > 0) gan.width = args.options.model.width;
  if (verb.count("--epochs") > 0) gan.epochs = args.options.epochs;
  if (verb.count("--batch") > 0) gan.batch = args.options.batch;
  if (verb.count("--lr") > 0) gan.learningRate = args.options.learningRate;
  gan.seed = args.options.seed;
  gan.threads = args.options.threads;
  gan.validate();
  core::checkOutputFolder(args.out);
  const learn::PredictionInputs inputs =
      learn::datasetPredictionInputs(args.patchModel, datasetFolder(args.dataset), {}, learn::Engine::OneDnn);
  learn::checkModelFolder(args.out,
                          {{"architecture", "gan"},
                           {"width", gan.width},
                           {"garment", inputs.data.garment.name},
                           {"vertices", inputs.data.garment.mesh.numVertices()}},
                          false, "a GAN blender");
  const stitch::GanReport report = stitch::trainGan(*inputs.model, inputs.data, gan, args.out);
  const stitch::GanEpoch& best = report.epochs[report.bestEpoch - 1];
  std::cout << std::fixed << std::setprecision(3) << "gan: epoch " << best.epoch << " of " << report.epochs.size()
            << ": regularisation " << best.regularisationErrorCm << " cm blended, " << best.stitchedErrorCm
            << " cm stitched -> " << report.folder.string() << " in " << std::setprecision(1) << report.seconds
            << " s\n";
}

void runTrain(TrainArgs args, const CLI::App& verb) {
  if (args.quiet) core::setLogLevel(core::LogLevel::Warning);
  if (args.model == "gan") return runTrainGan(std::move(args), verb);
  args.options.loss = learn::imageLossFromName(args.loss, "train --loss");
  args.options.targetScaling = learn::targetScalingFromName(args.targetScaling, "train --target-scaling");
  args.options.schedule = learn::scheduleFromName(args.schedule, "train --schedule");
  PIXELCLOTH_CHECK(args.patchModel.empty() && verb.count("--l1-weight") == 0,
                   "train --model " << args.model << ": --patch-model and --l1-weight are options of --model gan");
  args.options.model.architecture = learn::architectureFromName(args.model, "--model");
  args.options.patches = parsePatchList(args.patches);
  if (!args.space.empty()) args.options.space = learn::offsetSpaceFromName(args.space, "--space");
  args.options.residual = args.residual;
  const learn::TrainReport report = learn::train(datasetFolder(args.dataset), args.out, args.options);
  std::cout << std::fixed << std::setprecision(3);
  for (const learn::NetworkReport& n : report.networks) {
    std::ostringstream title;
    title << args.model << " width " << args.options.model.width
          << (n.patch >= 0 ? ", patch " + std::to_string(n.patch) : std::string());
    core::writePng(n.folder / "training.png", viz::renderTrainingCurves(n, title.str()));
    const learn::EpochRecord& best = n.epochs[n.bestEpoch - 1];
    std::cout << (n.patch >= 0 ? "patch " + std::to_string(n.patch) + ": " : std::string()) << "epoch " << best.epoch
              << " of " << n.epochs.size() << ": train " << best.trainErrorCm << " cm, regularisation "
              << best.regularisationErrorCm << " cm" << (n.stoppedEarly ? " (stopped early)" : "") << " -> "
              << n.folder.string() << "\n";
  }
  std::cout << report.networks.size() << " network(s) in " << std::setprecision(1) << report.seconds << " s\n";
}
}  // namespace

void registerTrain(CLI::App& app) {
  auto args = std::make_shared<TrainArgs>();
  const stitch::GanOptions gan;  // the blender's defaults, for the help of the options it shares
  auto ganDefault = [](auto value) {
    std::ostringstream text;
    text << " (gan: " << value << ")";
    return text.str();
  };
  CLI::App* verb = app.add_subcommand(
      "train",
      "Train a decoder or baseline on a dataset, or the GAN blender of a patch model; keep the best epoch by "
      "regularisation error; the decoders' runs are resumable");
  verb->add_option("--dataset", args->dataset, "Dataset folder (pixelcloth generate or dataset import)")->required();
  verb->add_option("--model", args->model,
                   "Network: whole (T-shirt, 6 x 256 x 256), patch (one per patch, 3 x 160 x 160 crops), necktie "
                   "(3 x 256 x 64), fc or fc-pca (2 x 256 ReLU to per-vertex values or 128 PCA coefficients), gan (the "
                   "U-Net blender of --patch-model's stitched predictions, 6 x 256 x 256)")
      ->check(CLI::IsMember({"whole", "patch", "necktie", "fc", "fc-pca", "gan"}))
      ->capture_default_str();
  verb->add_option("--patches", args->patches,
                   "Patch models: all, or ids such as 3,7 (one job of an array; runs fill one --out folder)")
      ->capture_default_str();
  verb->add_option("--width", args->options.model.width, "Multiplier of every channel count, (0, 4]" + ganDefault(gan.width))
      ->capture_default_str();
  verb->add_option("--min-channels", args->options.model.minChannels,
                   "Decoders: channels an upsampling layer keeps at the least, whatever the width (the paper's own "
                   "count where it is smaller); 0: the plain multiplier")
      ->capture_default_str();
  verb->add_option("--patch-model", args->patchModel,
                   "gan: the trained patch model (all 28 patches) whose stitched predictions of --dataset it blends");
  verb->add_option("--l1-weight", args->gan.l1Weight, "gan: weight of the masked L1 term (metres) against the "
                                                      "adversarial one")
      ->capture_default_str();
  verb->add_option("--components", args->options.model.pcaComponents, "fc-pca: PCA components of the train split")
      ->capture_default_str();
  verb->add_option("--space", args->space,
                   "Values: local (offsets in the embedded frames), root (offsets in the root frame) or positions "
                   "(fc, fc-pca); default local, root for the necktie")
      ->check(CLI::IsMember({"local", "root", "positions"}));
  verb->add_option("--residual", args->residual,
                   "Base folder of the dataset (reconstruct --write-base): learn ground truth minus the marker "
                   "reconstruction, with the marker features as extra inputs");
  verb->add_option("--loss", args->loss, "Image loss on the padded UV mask: l1 or l2")
      ->check(CLI::IsMember({"l1", "l2"}))
      ->capture_default_str();
  verb->add_option("--target-scaling", args->targetScaling,
                   "Decoders: none (learn offsets in metres) or per-channel (learn images of zero mean and unit "
                   "spread per channel, folded back into metres when saved)")
      ->check(CLI::IsMember({"none", "per-channel"}))
      ->capture_default_str();
  verb->add_option("--normal-weight", args->options.normalWeight,
                   "Weight of the normal loss, 0 to 1000000; default 0.01 (T-shirt), 0.1 (necktie)")
      ->check(CLI::Range(0.0, 1e6));
  verb->add_option("--edge-weight", args->options.edgeWeight,
                   "Weight of the edge-length loss, 0 to 1000000; default 0.1 (necktie), 0 (T-shirt)")
      ->check(CLI::Range(0.0, 1e6));
  verb->add_option("--epochs", args->options.epochs, "Passes over the train split" + ganDefault(gan.epochs))->capture_default_str();
  verb->add_option("--batch", args->options.batch, "Samples per Adam step" + ganDefault(gan.batch))->capture_default_str();
  verb->add_option("--lr", args->options.learningRate, "Adam's learning rate" + ganDefault(gan.learningRate))
      ->capture_default_str();
  verb->add_option("--schedule", args->schedule,
                   "Decoders and baselines: the learning rate over the run: constant, cosine (to zero at the last "
                   "step) or step (a tenth from half the epochs, a hundredth from three quarters)")
      ->check(CLI::IsMember({"constant", "cosine", "step"}))
      ->capture_default_str();
  verb->add_option("--patience", args->options.patience,
                   "Decoders and baselines: stop after this many epochs without a lower regularisation error (0: "
                   "run every epoch)")
      ->capture_default_str();
  verb->add_option("--train-samples", args->options.trainSamples,
                   "Decoders and baselines: learn from only the first N samples of the train split (0: all), for "
                   "learning curves; the regularisation and test splits stay whole")
      ->capture_default_str();
  verb->add_option("--seed", args->options.seed, "Seeds the weights and the order of the samples")
      ->capture_default_str();
  verb->add_option("--threads", args->options.threads, "LibTorch threads (0: one per core)")->capture_default_str();
  verb->add_option("--networks-at-once", args->options.networksAtOnce,
                   "Patch decoders trained at the same time, the threads shared out (0: one per thread; 1: one "
                   "after another on all threads)")
      ->capture_default_str();
  verb->add_option("--out", args->out,
                   "Model folder: model.tensors (best epoch), model.json, log.csv, training.png (the curves), "
                   "checkpoint.tensors (patch_NN/ per patch; gan: no checkpoint)")
      ->required();
  verb->add_flag("--quiet", args->quiet, "No progress on stderr");
  verb->callback([args, verb] { runTrain(*args, *verb); });
}

}  // namespace pixelcloth::apps
