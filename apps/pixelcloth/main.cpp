// pixelcloth: one command-line front end over the library; one file per verb, no algorithms here.
#include <exception>
#include <iostream>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "verbs.h"

int main(int argc, char** argv) {
  CLI::App app{"pixelcloth: data-driven garments in pattern space (pixel-based cloth)", "pixelcloth"};
  app.require_subcommand(1);
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet,
               "Silence progress and information on stderr (warnings that data was lost still show)");
  app.parse_complete_callback([&] {
    pixelcloth::core::setLogLevel(quiet ? pixelcloth::core::LogLevel::Warning : pixelcloth::core::LogLevel::Info);
  });

  pixelcloth::apps::registerBody(app);
  pixelcloth::apps::registerGarment(app);
  pixelcloth::apps::registerCage(app);
  pixelcloth::apps::registerDress(app);
  pixelcloth::apps::registerPose(app);
  pixelcloth::apps::registerDemo(app);
  pixelcloth::apps::registerBench(app);
  pixelcloth::apps::registerBases(app);
  pixelcloth::apps::registerImages(app);
  pixelcloth::apps::registerEdit(app);
  pixelcloth::apps::registerDataset(app);
  pixelcloth::apps::registerGenerate(app);
  pixelcloth::apps::registerReconstruct(app);
  pixelcloth::apps::registerModel(app);
  pixelcloth::apps::registerTrain(app);
  pixelcloth::apps::registerPredict(app);
  pixelcloth::apps::registerEvaluate(app);
  pixelcloth::apps::registerPca(app);
  pixelcloth::apps::registerStitch(app);
  for (CLI::App* verb : app.get_subcommands({})) verb->fallthrough();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;  // wrong command line: same exit code as any other bad input
  } catch (const pixelcloth::core::InputError& e) {
    std::cerr << "pixelcloth: error: " << e.what() << '\n';
    return 2;
  } catch (const pixelcloth::core::InternalError& e) {
    std::cerr << "pixelcloth: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "pixelcloth: internal error (a bug in pixelcloth, please report it): " << e.what() << '\n';
    return 1;
  }
  return 0;
}
