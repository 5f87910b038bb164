// pixelcloth: one command-line front end over the library; one file per verb, no algorithms here.
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/data/dataset.h"
#include "verbs.h"

namespace {
pixelcloth::body::BeyondLimits beyondLimits = pixelcloth::body::BeyondLimits::Refuse;
pixelcloth::data::Checksums datasetChecksums = pixelcloth::data::Checksums::Verify;
}  // namespace

pixelcloth::body::BeyondLimits pixelcloth::apps::poseLimits() { return beyondLimits; }
pixelcloth::data::DatasetFolder pixelcloth::apps::datasetFolder(const std::filesystem::path& path) {
  return {path, datasetChecksums};
}

int main(int argc, char** argv) {
  CLI::App app{"pixelcloth: data-driven garments in pattern space (pixel-based cloth)", "pixelcloth"};
  app.require_subcommand(1);
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet,
               "Silence progress and information on stderr (warnings that data was lost still show)");
  bool noVerify = false;
  app.add_flag("--no-verify", noVerify,
               "Read dataset files without checking them against manifest.json's sizes and CRC-32s first");
  bool clampToLimits = false;
  app.add_flag("--clamp-to-limits", clampToLimits,
               "Clamp joint angles of pose files that lie beyond the joints' limits into them (with a warning) "
               "instead of refusing the file");
  app.parse_complete_callback([&] {
    pixelcloth::core::setLogLevel(quiet ? pixelcloth::core::LogLevel::Warning : pixelcloth::core::LogLevel::Info);
    datasetChecksums = noVerify ? pixelcloth::data::Checksums::Skip : pixelcloth::data::Checksums::Verify;
    beyondLimits = clampToLimits ? pixelcloth::body::BeyondLimits::Clamp : pixelcloth::body::BeyondLimits::Refuse;
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
  pixelcloth::apps::registerPlot(app);
  pixelcloth::apps::registerView(app);
  pixelcloth::apps::registerExperiments(app);
  pixelcloth::apps::registerMotion(app);
  for (CLI::App* verb : app.get_subcommands({})) verb->fallthrough();
  // Seeds are unsigned 64-bit: "-1" would wrap to 2^64 - 1, and 2^64 or more saturate to it, each read as a valid,
  // different seed. Refuse both in every verb.
  const CLI::Validator nonNegative(
      [](std::string& value) {
        const std::string largest = "18446744073709551615";
        if (!value.empty() && value.front() == '-') return "a seed is a whole number of 0 or more, got " + value;
        const size_t digits =
            value.find_first_not_of('0') == std::string::npos ? 1 : value.size() - value.find_first_not_of('0');
        const std::string significant = value.substr(value.size() - digits);
        if (digits > largest.size() || (digits == largest.size() && significant > largest))
          return "a seed is at most " + largest + " (2^64 - 1), got " + value;
        return std::string();
      },
      "SEED 0 to 2^64 - 1");
  std::vector<CLI::App*> verbs = app.get_subcommands({});
  while (!verbs.empty()) {
    CLI::App* verb = verbs.back();
    verbs.pop_back();
    if (CLI::Option* seed = verb->get_option_no_throw("--seed")) seed->check(nonNegative);
    for (CLI::App* sub : verb->get_subcommands({})) verbs.push_back(sub);
  }

  // A word that names no verb: say so, with the verbs (CLI11 would say only that a subcommand is required). The
  // global options before the verb are flags, so the first word not starting with '-' is the verb.
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (!word.empty() && word.front() == '-') continue;
    bool known = false;
    std::string verbs;
    for (CLI::App* verb : app.get_subcommands({})) {
      known = known || verb->check_name(word);
      verbs += (verbs.empty() ? "" : ", ") + verb->get_name();
    }
    if (!known) {
      std::cerr << "pixelcloth: error: unknown verb '" << word << "'; the verbs are " << verbs
                << " (pixelcloth --help describes each)\n";
      return 2;
    }
    break;
  }
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
