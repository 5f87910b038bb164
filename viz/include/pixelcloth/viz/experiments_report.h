#pragma once

// The report of eval::runExperiments: results.md with every table of the paper beside ours, and its pictures.

#include <filesystem>

#include "pixelcloth/eval/experiments.h"

namespace pixelcloth::viz {

/// Writes `out`/results.md and `out`/figures/ (error_maps_whole.png and error_maps_patch.png: the test split's
/// per-vertex errors of the whole and patch CNNs; body_shapes.png: train and test error against the body shape), each
/// atomically. The tables put the paper's figures beside ours, say whether our ordering agrees with the paper's, and
/// give the dataset sizes, width, epochs, wall times and the equivalent commands.
void writeExperimentReport(const eval::ExperimentResults& results, const std::filesystem::path& out);

}  // namespace pixelcloth::viz
