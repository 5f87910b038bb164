// pixelcloth bases: the appendix's blendshape-basis figures (boundary data filled isotropically and anisotropically).
#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/viz/basis_figures.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct BasesArgs {
  std::string figures;
  viz::BasisFigureOptions options;
  double thetaDegrees = 30.0;
};

void runBases(const BasesArgs& args) {
  viz::BasisFigureOptions options = args.options;
  options.theta = args.thetaDegrees * 3.14159265358979323846 / 180.0;
  options.validate();
  core::checkOutputFolder(args.figures);
  core::checkRunFolder(args.figures, {"", {}, "the basis figures"});
  core::ensureOutputFolder(args.figures);
  PIXELCLOTH_INFO("bases: " << options.side << " m square, " << options.cells << " x " << options.cells
                            << " cells; anisotropic theta " << args.thetaDegrees << " deg, ratio " << options.ratio);
  std::vector<viz::BasisFigure> figures = viz::writeBasisFigures(args.figures, options);
  PIXELCLOTH_INFO("bases: " << figures.size() << " figures -> " << args.figures
                            << "/{<shape>_{iso,aniso}.png, <shape>_{iso,aniso}_3d.png, <shape>_{iso,aniso}.obj, "
                               "bases.png}; bases.png rows: one bump, two bumps, sine, S-curve; columns: isotropic "
                               "top view, isotropic 3D, anisotropic top view, anisotropic 3D");
}
}  // namespace

void registerBases(CLI::App& app) {
  auto args = std::make_shared<BasesArgs>();
  CLI::App* verb = app.add_subcommand(
      "bases",
      "Figures of the per-patch blendshape bases (paper's appendix): boundary data on a square patch filled "
      "by harmonic and anisotropic diffusion; PNG height maps, 3D views, OBJ surfaces, contact sheet");
  verb->add_option("--figures", args->figures, "Output folder for the figures")->required();
  verb->add_option("--side", args->options.side, "Side of the square patch, metres (0.001 to 100)")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 100.0));
  verb->add_option("--cells", args->options.cells, "Grid cells per side (4 triangles each)")
      ->capture_default_str()
      ->check(CLI::Range(2, 400));
  verb->add_option("--amplitude", args->options.amplitude, "Largest boundary height, metres (0.000001 to 10)")
      ->capture_default_str()
      ->check(CLI::Range(0.000001, 10.0));
  verb->add_option("--theta", args->thetaDegrees, "Anisotropic direction of faster diffusion, degrees from +u")
      ->capture_default_str();
  verb->add_option("--ratio", args->options.ratio, "Anisotropic diffusion across theta relative to along, (0, 1]")
      ->capture_default_str();
  verb->add_option("--size", args->options.pictureSize, "Side of each picture, pixels")
      ->capture_default_str()
      ->check(CLI::Range(32, 4096));
  verb->callback([args] { runBases(*args); });
}

}  // namespace pixelcloth::apps
