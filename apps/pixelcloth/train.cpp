// pixelcloth train: an image decoder learned from a dataset's cloth images (the whole garment or the necktie).
#include "pixelcloth/learn/train.h"

#include <iomanip>
#include <iostream>
#include <memory>

#include "pixelcloth/core/log.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct TrainArgs {
  std::string dataset, out, model = "whole";
  learn::TrainOptions options;
};

void runTrain(TrainArgs args) {
  if (args.options.quiet) core::setLogLevel(core::LogLevel::Warning);
  args.options.model.architecture = learn::architectureFromName(args.model, "--model");
  const learn::TrainReport report = learn::trainImageModel(args.dataset, args.out, args.options);
  const learn::EpochRecord& best = report.epochs[report.bestEpoch - 1];
  std::cout << std::fixed << std::setprecision(3) << "epoch " << best.epoch << " of " << report.epochs.size()
            << ": train " << best.trainErrorCm << " cm, regularisation " << best.regularisationErrorCm << " cm -> "
            << args.out << "/{model.pt, model.json, log.csv}\n";
}
}  // namespace

void registerTrain(CLI::App& app) {
  auto args = std::make_shared<TrainArgs>();
  CLI::App* verb = app.add_subcommand(
      "train", "Train an image decoder (whole garment or necktie) on a dataset's cloth images; keep the best epoch");
  verb->add_option("--dataset", args->dataset, "Dataset folder (pixelcloth generate or dataset import)")->required();
  verb->add_option("--model", args->model, "Network: whole (T-shirt, 256 x 256 x 6) or necktie (256 x 64 x 3)")
      ->check(CLI::IsMember({"whole", "necktie"}))
      ->capture_default_str();
  verb->add_option("--width", args->options.model.width, "Multiplier of every channel count, (0, 4]")
      ->capture_default_str();
  verb->add_option("--loss", args->options.loss, "Image loss on the padded UV mask: l1 or l2")
      ->check(CLI::IsMember({"l1", "l2"}))
      ->capture_default_str();
  verb->add_option("--epochs", args->options.epochs, "Passes over the train split")->capture_default_str();
  verb->add_option("--batch", args->options.batch, "Samples per Adam step")->capture_default_str();
  verb->add_option("--lr", args->options.learningRate, "Adam's learning rate")->capture_default_str();
  verb->add_option("--seed", args->options.seed, "Seeds the weights and the order of the samples")
      ->capture_default_str();
  verb->add_option("--out", args->out,
                   "Model folder: model.pt (best epoch by regularisation error), model.json, log.csv")
      ->required();
  verb->add_flag("--quiet", args->options.quiet, "No progress on stderr");
  verb->callback([args] { runTrain(*args); });
}

}  // namespace pixelcloth::apps
