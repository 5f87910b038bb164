#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "pixelcloth/body/body.h"
#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/sim/garment_sim.h"

namespace pixelcloth::sim {

/// Settings of `pixelcloth generate` (DESIGN.md, "Simulation").
/// The most samples one dataset holds (`generate --count`): ten million T-shirt samples are 720 GB of positions and
/// offsets.
constexpr int kMaxGenerateCount = 10000000;

struct GenerateOptions {
  /// What --garment names: a template ("tshirt", "necktie") or a garment folder (garment::resolveGarment).
  std::string garment = "tshirt";
  int count = 0;                   ///< N: samples in the whole dataset
  std::uint64_t seed = 0;
  std::string shard = "0/1";         ///< "K/N": this job's slice of [0, count)
  std::filesystem::path bodyFolder;  ///< a body folder (`pixelcloth body`); empty: the built-in mannequin
  double bodyShape = 0;              ///< mannequin girth in [-1, 2] (ignored with a body folder)
  std::string corruptWeights;        ///< "", "torso" or "torso+arm" (body::corruptUpperArmWeights)
  double corruptFraction = 0.5;
  int threads = 0;                ///< worker threads; 0: one per core
  int maxAttempts = 50;           ///< draws per sample before giving up (InputError)
  double mannequinEdge = 0.0075;  ///< mannequin triangle size (tests use coarser bodies)
  SimulationOptions simulation;
  void validate() const;
};

/// The solver settings a dataset made with `options` records (its manifest's "settings"): which solver, its material,
/// contact and stopping settings, the continuation schedule and the acceptance test.
nlohmann::json simulationSettings(const SimulationOptions& options);

/// The pose drawn for sample `index` at its `attempt`-th try: a PoseSampler seeded from (seed, index, attempt), so a
/// sample's pose does not depend on which shard or thread makes it. Only the joints that drive the garment move
/// (`traits.poseJoints`: the necktie's centre line); arm poses are pruned against the torso only when the arms drive
/// it. Sets `pruned` to the number of draws the sampler discarded (arm inside the torso) before this one.
body::Pose samplePose(const body::Body& body, const garment::GarmentTraits& traits, std::uint64_t seed, int index,
                      int attempt, int* pruned = nullptr);

/// The draws behind a simulated dataset's samples, made again from its seed (samplePose is a function of the seed, the
/// sample index and the attempt): every pose the sampler drew for them (`drawn`), those its arm prune let through to
/// the simulation (`simulated`), and the samples' own poses (`kept`). A sample's attempts before the one it holds
/// were rejected by the simulation. For the appendix's joint-angle histograms before and after filtering.
struct SampledPoses {
  std::vector<body::Pose> drawn, simulated, kept;
};
/// Throws InputError naming the dataset when a sample's pose is not among the first `maxAttempts` attempts of its
/// index (a dataset of another seed or sampler, or not simulated).
SampledPoses datasetPoseDraws(const data::Dataset& dataset, const body::Body& body,
                              const garment::GarmentTraits& traits, int maxAttempts = 50);

/// What a generate run did.
struct GenerateReport {
  int added = 0;    ///< samples simulated and added in this run
  int resumed = 0;  ///< samples found done from an earlier run
  int rejected = 0;
  double seconds = 0;
};

/// Makes (or resumes) a dataset folder: builds or loads the body, builds the garment, dresses it, settles it, then
/// simulates every pending sample of the shard on `threads` threads, each pose drawn by `samplePose` and redrawn
/// (next attempt) while the simulation rejects it; progress with rate and ETA on stderr (core::Progress, silent below
/// the Info log level). Ends with the finished folder (sim/dataset.h, docs/dataset.md).
GenerateReport generateDataset(const std::filesystem::path& out, const GenerateOptions& options);

/// Simulates `garment` (dressed by `dressing`) on `body` in every one of `poses` on `threads` threads (0: one per
/// core), with progress on stderr: each pose's sample (statistics, rejection included, positions and offsets), in
/// the order given. No pose is redrawn: for rejection rates over a fixed set of poses.
std::vector<data::Sample> simulatePoseSamples(const body::Body& body, const garment::Garment& garment,
                                              const cage::Dressing& dressing, const std::vector<body::Pose>& poses,
                                              const SimulationOptions& options = {}, int threads = 0);
/// The same, the statistics only.
std::vector<data::SampleStats> simulatePoses(const body::Body& body, const garment::Garment& garment,
                                             const cage::Dressing& dressing, const std::vector<body::Pose>& poses,
                                             const SimulationOptions& options = {}, int threads = 0);

}  // namespace pixelcloth::sim
