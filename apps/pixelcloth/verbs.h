#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/data/dataset.h"

namespace pixelcloth::apps {

/// Help of every --garment option: what garment::resolveGarment takes.
inline constexpr const char* kGarmentHelp =
    "Garment: a template (tshirt or necktie) or a garment folder (garment.obj + garment.json, from "
    "`pixelcloth garment --out`, a template or --import)";

/// What the program-wide --clamp-to-limits asks of every pose file a verb reads (body::readPose), set once the
/// command line is parsed.
body::BeyondLimits poseLimits();

/// The dataset folder `path`, read as the program-wide --no-verify asks (checksums verified unless it is given).
data::DatasetFolder datasetFolder(const std::filesystem::path& path);

/// Each verb lives in its own file and adds one subcommand to the `pixelcloth` app. The callback
/// runs the verb; it throws `core::InputError` for bad input (exit code 2).
void registerBody(CLI::App& app);
void registerGarment(CLI::App& app);
void registerPose(CLI::App& app);
void registerDemo(CLI::App& app);
void registerBench(CLI::App& app);
void registerBases(CLI::App& app);
void registerImages(CLI::App& app);
void registerEdit(CLI::App& app);
void registerCage(CLI::App& app);
void registerDress(CLI::App& app);
void registerDataset(CLI::App& app);
void registerGenerate(CLI::App& app);
/// `markers` and `reconstruct` (DESIGN.md, "Key-point-to-cage spline solver").
void registerReconstruct(CLI::App& app);
/// `model` and `train` (learn/): a network's size; training an image decoder.
void registerModel(CLI::App& app);
void registerTrain(CLI::App& app);
/// `predict` and `evaluate` (learn/, stitch/): garments from a trained model; its errors on a split.
void registerPredict(CLI::App& app);
void registerEvaluate(CLI::App& app);
void registerPca(CLI::App& app);
void registerStitch(CLI::App& app);
/// `plot`: a line chart of a small JSON table.
void registerPlot(CLI::App& app);
/// `view`: an output folder as a static three.js page (viz/viewer.h).
void registerView(CLI::App& app);
void registerExperiments(CLI::App& app);
/// `motion import`: a motion-capture clip retargeted to the body (motion/).
void registerMotion(CLI::App& app);

}  // namespace pixelcloth::apps
