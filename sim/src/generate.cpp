#include "pixelcloth/sim/generate.h"

#include <atomic>
#include <chrono>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/parallel.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/sim/pose_sampler.h"

namespace pixelcloth::sim {

namespace {

/// SplitMix64 finaliser: spreads (seed, index, attempt) into independent sampler seeds.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

body::Body makeBody(const GenerateOptions& options, nlohmann::json& description) {
  body::Body body;
  if (!options.bodyFolder.empty()) {
    body = body::loadBody(options.bodyFolder);
    description = {{"kind", "folder"}, {"folder", options.bodyFolder.string()}};
  } else {
    body::MannequinOptions mannequin;
    mannequin.shape = options.bodyShape;
    mannequin.edgeLength = options.mannequinEdge;
    body = body::makeMannequin(mannequin);
    description = {{"kind", "mannequin"}, {"shape", options.bodyShape}, {"edge_length", options.mannequinEdge}};
  }
  if (!options.corruptWeights.empty()) {
    body.weights =
        body::corruptUpperArmWeights(body.skeleton, body.weights, options.corruptWeights, options.corruptFraction);
    description["corrupt_weights"] = {{"mode", options.corruptWeights}, {"fraction", options.corruptFraction}};
  }
  return body;
}

/// Runs job(simulator, k) for every k in [0, count) on `threads` threads, the calling one with `first`, each other
/// with its own simulator built from `first`'s settled drape (so a result does not depend on the thread). The first
/// exception stops the others and is rethrown.
void forEachOnSimulators(GarmentSimulator& first, const body::Body& body, const garment::Garment& garment,
                         const cage::Dressing& dressing, const SimulationOptions& options, int count, int threads,
                         const std::function<void(GarmentSimulator&, int)>& job) {
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto work = [&](GarmentSimulator& simulator) {
    try {
      for (int k = next++; k < count; k = next++) job(simulator, k);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failureMutex);
      if (!failure) failure = std::current_exception();
      next = count;
    }
  };
  std::vector<std::unique_ptr<GarmentSimulator>> simulators;
  for (int t = 1; t < threads; ++t)
    simulators.push_back(std::make_unique<GarmentSimulator>(body, garment, dressing, options, &first.restDrape()));
  std::vector<std::thread> workers;
  for (auto& simulator : simulators) workers.emplace_back(work, std::ref(*simulator));
  work(first);
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace

nlohmann::json simulationSettings(const SimulationOptions& s) {
  if (s.kind == SolverKind::Newton) {
    const NewtonSchedule& n = s.newton;
    const EquilibriumOptions& q = n.solver;
    return {{"solver", "newton"},
            {"method", std::string("Newton, projected Hessian, CHOLMOD; IPC barrier contact, ") +
                           (q.friction > 0 ? "lagged friction, eased to the Coulomb bound" : "frictionless") +
                           "; pattern rest shape"},
            {"stretch_stiffness_n_per_m", q.stretchStiffness},
            {"compression_ratio", q.compressionRatio},
            {"bend_stiffness_n_m", q.bendStiffness},
            {"density_kg_per_m2", q.density},
            {"gravity", q.gravity},
            {"barrier_distance_m", q.barrierDistance},
            {"barrier_stiffness_n_per_m3", q.barrierStiffness},
            {"friction", q.friction},
            {"friction_slip_m", q.frictionSlip},
            {"force_tolerance_of_weight", q.forceTolerance},
            {"step_expansions", q.stepExpansions},
            {"max_penetration_m", s.maxPenetration},
            {"step_degrees", n.stepDegrees},
            {"iterations_per_step", n.iterationsPerStep},
            {"step_tolerance_of_weight", n.stepTolerance},
            {"final_iterations", n.finalIterations},
            {"friction_lags", n.frictionLags},
            {"friction_ease", n.frictionEase},
            {"rest_iterations", n.restIterations},
            {"min_area_ratio", s.minAreaRatio},
            {"max_area_ratio", s.maxAreaRatio},
            {"pinned_vertices", s.pinned.size()},
            {"pose_sampler", "appendix: half-normal centre line, azimuth / sine-altitude / twist arms, pruned"}};
  }
  const QuasistaticOptions& q = s.solver;
  return {{"solver", "projective dynamics, proximal, pattern rest shape"},
          {"stretch_stiffness_n_per_m", q.stretchStiffness},
          {"bend_stiffness_n_m", q.bendStiffness},
          {"density_kg_per_m2", q.density},
          {"gravity", q.gravity},
          {"time_scale_s", q.timeScale},
          {"contact_offset_m", q.contactOffset},
          {"contact_stiffness_n_per_m", q.contactStiffness},
          {"friction", q.friction},
          {"max_penetration_m", s.maxPenetration},
          {"tolerance_m", q.tolerance},
          {"step_degrees", s.stepDegrees},
          {"iterations_per_step", s.iterationsPerStep},
          {"final_iterations", s.finalIterations},
          {"final_recheck_every", s.finalRecheckEvery},
          {"extra_iterations", s.extraIterations},
          {"extra_round", s.extraRound},
          {"min_area_ratio", s.minAreaRatio},
          {"max_area_ratio", s.maxAreaRatio},
          {"pinned_vertices", s.pinned.size()},
          {"pose_sampler", "appendix: half-normal centre line, azimuth / sine-altitude / twist arms, pruned"}};
}

void GenerateOptions::validate() const {
  PIXELCLOTH_CHECK(!garment.empty(), "generate: --garment is empty; expected a template name or a garment folder");
  PIXELCLOTH_CHECK(count >= 1 && count <= kMaxGenerateCount,
                   "generate: --count " << count << ", expected 1 to " << kMaxGenerateCount);
  PIXELCLOTH_CHECK(threads >= 0, "generate: --threads must be >= 0, got " << threads);
  PIXELCLOTH_CHECK(maxAttempts >= 1, "generate: max attempts must be >= 1");
  PIXELCLOTH_CHECK(corruptWeights.empty() || corruptWeights == "torso" || corruptWeights == "torso+arm",
                   "generate: --corrupt-weights must be torso or torso+arm, got '" << corruptWeights << "'");
  data::parseShard(shard);
  simulation.validate();
}

namespace {

/// The sampler of sample `index`'s `attempt`-th try.
PoseSamplerOptions samplerOptions(const garment::GarmentTraits& traits, std::uint64_t seed, int index, int attempt) {
  PoseSamplerOptions options;
  options.seed = mix(mix(seed) ^ mix(static_cast<std::uint64_t>(index) * 1000003ULL + attempt));
  options.prune = traits.armsDrive();  // a garment the arms do not move: arm pruning would not matter
  return options;
}

/// The joints the garment does not follow held at rest.
body::Pose heldAtRest(body::Pose pose, const garment::GarmentTraits& traits) {
  for (size_t j = traits.poseJoints; j < pose.rotations.size(); ++j) pose.rotations[j].setIdentity();
  return pose;
}

}  // namespace

body::Pose samplePose(const body::Body& body, const garment::GarmentTraits& traits, std::uint64_t seed, int index,
                      int attempt, int* pruned) {
  PoseSampler sampler(body, samplerOptions(traits, seed, index, attempt));
  const body::Pose pose = sampler.next();
  if (pruned) *pruned = sampler.stats().rejectedArmInsideTorso;
  return heldAtRest(pose, traits);
}

SampledPoses datasetPoseDraws(const data::Dataset& dataset, const body::Body& body,
                              const garment::GarmentTraits& traits, int maxAttempts) {
  const data::DatasetSettings& settings = dataset.info.settings;
  PIXELCLOTH_CHECK(settings.source == "simulated", dataset.info.folder.string()
                                                       << ": its samples were not simulated by pixelcloth ("
                                                       << settings.source << "): no sampler draws to make again");
  SampledPoses out;
  for (int row = 0; row < dataset.rows(); ++row) {
    const int index = settings.first() + row;
    const Eigen::VectorXf held = dataset.pose(row);
    bool found = false;
    for (int attempt = 0; attempt < maxAttempts && !found; ++attempt) {
      // As samplePose draws: raw draws until one passes the arm prune (PoseSampler::next).
      const PoseSamplerOptions options = samplerOptions(traits, settings.seed, index, attempt);
      PoseSampler sampler(body, options);
      for (int draw = 0; draw < options.maxAttempts; ++draw) {
        const body::Pose raw = sampler.draw();
        const body::Pose pose = heldAtRest(raw, traits);
        out.drawn.push_back(pose);
        if (options.prune && sampler.armInsideTorso(raw)) continue;
        out.simulated.push_back(pose);
        if (pose.toVector().head(held.size()) == held) {
          out.kept.push_back(pose);
          found = true;
        }
        break;
      }
    }
    PIXELCLOTH_CHECK(found, dataset.info.folder.string()
                                << ": sample " << index << "'s pose is none of the sampler's first " << maxAttempts
                                << " attempts from seed " << settings.seed
                                << ": made by another seed or sampler than pixelcloth generate's");
  }
  return out;
}

GenerateReport generateDataset(const std::filesystem::path& out, const GenerateOptions& given) {
  GenerateOptions options = given;
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  const garment::Garment garment = garment::resolveGarment(options.garment, "generate: --garment");
  nlohmann::json bodyDescription;
  const body::Body body = makeBody(options, bodyDescription);
  if (options.simulation.pinned.empty()) options.simulation.pinned = garment.traits.pinned;

  data::DatasetSettings settings;
  settings.garment = garment.name;
  settings.poseSize = garment.traits.poseSize();
  settings.vertexCount = garment.mesh.numVertices();
  settings.seed = options.seed;
  settings.count = options.count;
  settings.shard = data::parseShard(options.shard);
  settings.body = bodyDescription;
  settings.generator = simulationSettings(options.simulation);
  settings.source = "simulated";

  PIXELCLOTH_INFO("generate: dressing " << garment.name << " on the body");
  const cage::Dressing dressing = cage::dressGarment(body, cage::bodyCage(body), garment, cage::garmentCage(garment));
  const std::string advice = cage::fitAdvice(dressing);
  if (!advice.empty()) PIXELCLOTH_WARN("generate: " << advice);
  data::DatasetWriter writer(out, settings, body, garment, dressing.relaxed, dressing.embedding);
  const std::vector<int> pending = writer.pending();
  GenerateReport report;
  report.resumed = writer.done();
  if (!pending.empty()) {
    const int threads = core::threadCount(options.threads, static_cast<int>(pending.size()));
    PIXELCLOTH_INFO("generate: settling the garment in the rest pose");
    GarmentSimulator first(body, garment, dressing, options.simulation);
    const data::SampleStats& rest = first.restStats();
    const bool newton = options.simulation.kind == SolverKind::Newton;
    if (!first.restSettled() && newton)
      PIXELCLOTH_WARN("generate: the rest drape did not settle: the Newton solver stopped at its cap of "
                      << options.simulation.newton.restIterations << " iterations with a net force of "
                      << 100 * rest.residualForceRatio << "% of a vertex's weight left (" << rest.seconds
                      << " s); the samples start from this drape"
                      << (advice.empty() ? "" : " (the garment does not fit the body: see above)"));
    else if (!first.restSettled())
      PIXELCLOTH_WARN("generate: the rest drape did not settle: the solver stopped at its cap of "
                      << options.simulation.restIterations << " iterations with vertices still moving "
                      << 1000 * rest.residual << " mm an iteration (" << rest.seconds
                      << " s); the samples start from this drape"
                      << (advice.empty() ? "" : " (the garment does not fit the body: see above)"));
    else
      PIXELCLOTH_INFO("generate: rest drape settled in " << rest.iterations << " iterations (" << rest.seconds
                                                         << " s)");
    PIXELCLOTH_INFO("generate: " << pending.size() << " samples on " << threads << " threads");
    std::unique_ptr<core::Progress> progress;
    progress = std::make_unique<core::Progress>("generate " + garment.name, static_cast<int>(pending.size()));
    std::atomic<int> rejected{0};
    std::mutex progressMutex;
    forEachOnSimulators(
        first, body, garment, dressing, options.simulation, static_cast<int>(pending.size()), threads,
        [&](GarmentSimulator& simulator, int k) {
          const int index = pending[k];
          bool done = false;
          for (int attempt = 0; attempt < options.maxAttempts && !done; ++attempt) {
            int pruned = 0;
            const body::Pose pose = samplePose(body, garment.traits, options.seed, index, attempt, &pruned);
            for (int p = 0; p < pruned; ++p) writer.countRejection(data::Rejection::ArmInsideTorso);
            const data::Sample sample = simulator.simulate(pose);
            if (sample.stats.rejection != data::Rejection::None) {
              writer.countRejection(sample.stats.rejection);
              ++rejected;
              continue;
            }
            writer.add(index, sample);
            done = true;
          }
          PIXELCLOTH_CHECK(done, "generate: sample " << index << " was rejected " << options.maxAttempts
                                                     << " times in a row; the garment or body is unsuitable");
          if (progress) {
            std::lock_guard<std::mutex> lock(progressMutex);
            progress->advance();
          }
        });
    if (progress) progress->finish();
    report.added = static_cast<int>(pending.size());
    report.rejected = rejected;
  }
  writer.finish();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace pixelcloth::sim

namespace pixelcloth::sim {

std::vector<data::Sample> simulatePoseSamples(const body::Body& body, const garment::Garment& garment,
                                              const cage::Dressing& dressing, const std::vector<body::Pose>& poses,
                                              const SimulationOptions& options, int threads) {
  std::vector<data::Sample> samples(poses.size());
  if (poses.empty()) return samples;
  GarmentSimulator first(body, garment, dressing, options);
  std::unique_ptr<core::Progress> progress;
  progress = std::make_unique<core::Progress>("simulate " + garment.name, static_cast<int>(poses.size()));
  std::mutex progressMutex;
  forEachOnSimulators(first, body, garment, dressing, options, static_cast<int>(poses.size()),
                      core::threadCount(threads, static_cast<int>(poses.size())),
                      [&](GarmentSimulator& simulator, int k) {
                        samples[k] = simulator.simulate(poses[k]);
                        if (progress) {
                          std::lock_guard<std::mutex> lock(progressMutex);
                          progress->advance();
                        }
                      });
  if (progress) progress->finish();
  return samples;
}

std::vector<data::SampleStats> simulatePoses(const body::Body& body, const garment::Garment& garment,
                                             const cage::Dressing& dressing, const std::vector<body::Pose>& poses,
                                             const SimulationOptions& options, int threads) {
  std::vector<data::SampleStats> stats;
  for (const data::Sample& sample : simulatePoseSamples(body, garment, dressing, poses, options, threads))
    stats.push_back(sample.stats);
  return stats;
}

}  // namespace pixelcloth::sim
