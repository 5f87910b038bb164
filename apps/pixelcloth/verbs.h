#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>

#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/body/body.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::apps {

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
/// `markers` and `reconstruct` (issue 5).
void registerReconstruct(CLI::App& app);

/// Writes cage.json, patches.json and cage.png of a garment into `out` (the `cage` verb's outputs; the demo's too).
void writeCageFolder(const garment::Garment& garment, const std::filesystem::path& out, int size = 512);

/// Writes the `dress` verb's outputs for a garment dressed on `body` into `out`, each file atomically: dressed.obj
/// (the relaxed positions with the garment's UVs), area_distortion.png (viz::renderAreaDistortion), dressed.png (the
/// dressed garment on the body, three views) and dressing.json (iterations, residual, area-ratio statistics before and
/// after relaxation, vertices pushed out and their deepest penetration, vertices still inside, vertices per part).
void writeDressingFolder(const body::Body& body, const garment::Garment& garment, const cage::Dressing& dressing,
                         const std::filesystem::path& out);

}  // namespace pixelcloth::apps
