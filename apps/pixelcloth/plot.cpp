// pixelcloth plot: a line chart (PNG) of a small JSON table, for figures such as error against body shape.
#include <iostream>
#include <memory>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/viz/line_chart.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct PlotArgs {
  std::string table, out;
  int width = 640, height = 400;
  bool quiet = false;
};

void runPlot(const PlotArgs& args) {
  const std::string name = std::filesystem::path(args.table).filename().string();
  const viz::LineChart chart = viz::lineChartFromJson(core::readJson(args.table), name);
  PIXELCLOTH_CHECK(std::filesystem::path(args.out).extension() == ".png",
                   "--out " << args.out << ": expected a .png file name");
  core::writePng(args.out, viz::renderLineChart(chart, args.width, args.height));
  if (!args.quiet) std::cout << chart.series.size() << " series -> " << args.out << "\n";
}
}  // namespace

void registerPlot(CLI::App& app) {
  auto args = std::make_shared<PlotArgs>();
  CLI::App* verb = app.add_subcommand(
      "plot", "A line chart (PNG) of a JSON table {title, x_label, y_label, series: [{name, x: [...], y: [...]}]}");
  verb->add_option("--table", args->table, "The JSON table")->required();
  verb->add_option("--out", args->out, "The PNG to write (written under a temporary name, then renamed)")->required();
  verb->add_option("--width", args->width, "Pixels")->capture_default_str()->check(CLI::Range(320, 4096));
  verb->add_option("--height", args->height, "Pixels")->capture_default_str()->check(CLI::Range(200, 4096));
  verb->add_flag("--quiet", args->quiet, "Print nothing");
  verb->callback([args] { runPlot(*args); });
}

}  // namespace pixelcloth::apps
