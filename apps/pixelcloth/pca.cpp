// pixelcloth pca: the PCA filter of a dataset's train split, for evaluate/predict/stitch --stitch pca:K.
#include <iomanip>
#include <iostream>
#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/stitch/pca_filter.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct PcaArgs {
  std::string dataset, out, space = "local", base, method = "randomized";
  int rank = 0;
  bool quiet = false;
};

void runPca(const PcaArgs& args) {
  if (args.quiet) core::setLogLevel(core::LogLevel::Warning);
  core::checkOutputFolder(args.out);
  // A filter replaces every file of an earlier one; it refuses a folder holding any other kind of run.
  core::checkRunFolder(args.out, {"pca.json", {}, "a PCA filter"});
  const learn::PcaMethod method = learn::pcaMethodFromName(args.method, "--method");
  const learn::TrainingData data = learn::loadTrainingData(
      datasetFolder(args.dataset), learn::offsetSpaceFromName(args.space, "--space"), args.base);
  const stitch::PcaFilter filter = stitch::PcaFilter::fit(data, args.rank, method);
  filter.save(args.out);
  const Eigen::VectorXf& variance = filter.basis().variance;
  std::cout << std::setprecision(3) << "rank " << filter.rank() << " of " << data.train.size() << " train samples x "
            << 3 * data.garment.mesh.numVertices() << " values (" << args.method << ", "
            << filter.info()["seconds"].get<double>() << " s); variance of the first component " << variance(0)
            << " m^2, of the last " << variance(variance.size() - 1) << " -> " << args.out << "/pca.json\n";
}
}  // namespace

void registerPca(CLI::App& app) {
  auto args = std::make_shared<PcaArgs>();
  CLI::App* verb = app.add_subcommand(
      "pca", "Fit the PCA filter of a dataset's train split (evaluate/predict/stitch --stitch pca:K --pca DIR)");
  verb->add_option("--dataset", args->dataset, "Dataset folder")->required();
  verb->add_option("--out", args->out, "Output folder: pca.json, mean.npy, components.npy, variance.npy")->required();
  verb->add_option("--rank", args->rank, "Components kept (0: min(2048, train samples, 3 x vertices))")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--space", args->space, "Values: local, root or positions (the model's space)")
      ->check(CLI::IsMember({"local", "root", "positions"}))
      ->capture_default_str();
  verb->add_option("--base", args->base, "Residual models: the dataset's base folder the model was trained with");
  verb->add_option("--method", args->method,
                   "randomized (range finder, fast), gram (Gram matrix + LAPACK eigensolver) or svd (exact, slow)")
      ->check(CLI::IsMember({"randomized", "gram", "svd"}))
      ->capture_default_str();
  verb->add_flag("--quiet", args->quiet, "No progress on stderr");
  verb->callback([args] { runPca(*args); });
}

}  // namespace pixelcloth::apps
