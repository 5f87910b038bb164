// pixelcloth view: an output folder as a static page to turn around in a browser (three.js, no server, no network).
#include <iostream>
#include <memory>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/viz/viewer.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
namespace fs = std::filesystem;

struct ViewArgs {
  std::string folder, out;
  int maxScenes = 24;
};

void runView(const ViewArgs& args) {
  const fs::path out = args.out.empty() ? fs::path(args.folder) / "view" : fs::path(args.out);
  core::checkRunFolder(out, {"", {}, "a viewer page"});
  viz::ViewOptions options;
  options.maxScenes = args.maxScenes;
  const viz::ViewSite site = viz::viewFolder(args.folder, options);
  viz::writeViewSite(out, site);
  std::cout << site.title << ": " << site.scenes.size() << " scene" << (site.scenes.size() == 1 ? "" : "s") << " -> "
            << (out / "index.html").string() << " (open it in a browser; no server needed)\n";
}
}  // namespace

void registerView(CLI::App& app) {
  auto args = std::make_shared<ViewArgs>();
  CLI::App* verb = app.add_subcommand(
      "view",
      "An output folder (dataset, evaluate, predict, reconstruct, a motion prediction, the demo's report) as "
      "a 3D viewer page: index.html, three.js and one .glb per scene");
  verb->add_option("folder", args->folder, "The output folder to show")->required();
  CLI::Option* out = verb->add_option("--out", args->out, "The site's folder (default: FOLDER/view)");
  verb->add_option("--max-scenes", args->maxScenes,
                   "Samples shown of a dataset or an evaluation, spread over its rows (a report folder: at most 4 "
                   "of each)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  verb->callback([args, out] {
    PIXELCLOTH_CHECK(out->count() == 0 || !args->out.empty(),
                     "view --out \"\": an empty folder name (leave --out out for FOLDER/view)");
    runView(*args);
  });
}

}  // namespace pixelcloth::apps
