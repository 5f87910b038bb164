#include "pixelcloth/sim/garment_sim.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::sim {

namespace {

const core::EnumNames<SolverKind, 2> kSolverKinds{
    "solver", {{{SolverKind::ProjectiveDynamics, "pd"}, {SolverKind::Newton, "newton"}}}};

/// The pose a fraction `t` of the way from the rest pose: every joint rotation scaled along its own axis.
body::Pose partialPose(const body::Pose& pose, double t) {
  body::Pose result = body::Pose::identity();
  for (size_t j = 0; j < pose.rotations.size(); ++j) {
    const Eigen::AngleAxisd full(pose.rotations[j]);
    result.rotations[j] = Eigen::AngleAxisd(t * full.angle(), full.axis()).toRotationMatrix();
  }
  return result;
}

/// The largest joint rotation angle of a pose (degrees).
double largestJointAngle(const body::Pose& pose) {
  double largest = 0;
  for (const Eigen::Matrix3d& rotation : pose.rotations)
    largest = std::max(largest, Eigen::AngleAxisd(rotation).angle() * 180.0 / M_PI);
  return largest;
}

}  // namespace

const char* solverKindName(SolverKind kind) { return kSolverKinds.name(kind); }

SolverKind parseSolverKind(const std::string& name, const std::string& context) {
  return kSolverKinds.fromName(name, context);
}

void NewtonSchedule::validate() const {
  solver.validate();
  PIXELCLOTH_CHECK(iterationsPerStep >= 1 && finalIterations >= 1 && restIterations >= 1,
                   "simulation: Newton iteration counts must be positive");
  PIXELCLOTH_CHECK(stepTolerance > 0 && std::isfinite(stepTolerance),
                   "simulation: step tolerance must be positive, got " << stepTolerance);
  PIXELCLOTH_CHECK(frictionLags >= 0, "simulation: friction lags must be >= 0, got " << frictionLags);
  PIXELCLOTH_CHECK(frictionEase > 0 && frictionEase <= 1,
                   "simulation: friction ease must be in (0, 1], got " << frictionEase);
  PIXELCLOTH_CHECK(stepDegrees > 0 && stepDegrees <= 180,
                   "simulation: step must be in (0, 180] degrees, got " << stepDegrees);
}

void SimulationOptions::validate() const {
  if (kind == SolverKind::Newton) newton.validate();
  solver.validate();
  PIXELCLOTH_CHECK(stepDegrees > 0 && stepDegrees <= 180,
                   "simulation: step must be in (0, 180] degrees, got " << stepDegrees);
  PIXELCLOTH_CHECK(iterationsPerStep >= 1 && finalIterations >= 1 && restIterations >= 1,
                   "simulation: iteration counts must be positive");
  PIXELCLOTH_CHECK(extraIterations >= 0 && extraRound >= 1,
                   "simulation: need extra iterations >= 0 and an extra round >= 1, got " << extraIterations << " and "
                                                                                          << extraRound);
  PIXELCLOTH_CHECK(
      minAreaRatio > 0 && minAreaRatio < 1 && maxAreaRatio > 1,
      "simulation: need 0 < min area ratio < 1 < max area ratio, got " << minAreaRatio << " and " << maxAreaRatio);
  PIXELCLOTH_CHECK(finalRecheckEvery >= 1, "simulation: final recheck interval must be >= 1, got " << finalRecheckEvery);
  PIXELCLOTH_CHECK(maxPenetration > 0, "simulation: max penetration must be positive, got " << maxPenetration);
}

GarmentSimulator::GarmentSimulator(const body::Body& body, const garment::Garment& garment,
                                   const cage::Dressing& dressing, const SimulationOptions& options,
                                   const Eigen::MatrixX3d* settled)
    : body_(body), garment_(garment), dressing_(dressing), options_(options) {
  options_.validate();
  const int n = garment.mesh.numVertices();
  PIXELCLOTH_CHECK(
      dressing.relaxed.rows() == n && dressing.embedding.size() == n && static_cast<int>(dressing.part.size()) == n,
      "simulation: the dressing has " << dressing.relaxed.rows() << " vertices, the garment " << n);
  dressing.embedding.validate(body.mesh.numFaces(), "simulation: dressing");
  if (options_.kind == SolverKind::Newton)
    newton_ = std::make_unique<EquilibriumSolver>(garment.mesh, options_.pinned, options_.newton.solver);
  else
    solver_ = std::make_unique<QuasistaticSolver>(garment.mesh, options_.pinned, options_.solver);

  // One collider per body part, with its own compact vertex numbering.
  std::vector<Collider> colliders;
  for (const body::BodyPart& part : body.parts) {
    std::vector<int> local(body.mesh.numVertices(), -1);
    std::vector<int>& vertices = partVertices_.emplace_back();
    Collider collider;
    collider.F.resize(static_cast<int>(part.faces.size()), 3);
    for (size_t f = 0; f < part.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int v = body.mesh.F(part.faces[f], k);
        if (local[v] < 0) {
          local[v] = static_cast<int>(vertices.size());
          vertices.push_back(v);
        }
        collider.F(static_cast<int>(f), k) = local[v];
      }
    collider.V.resize(static_cast<int>(vertices.size()), 3);
    for (size_t i = 0; i < vertices.size(); ++i) collider.V.row(static_cast<int>(i)) = body.mesh.V.row(vertices[i]);
    colliders.push_back(std::move(collider));
  }
  for (const int p : dressing.part)
    PIXELCLOTH_CHECK(p >= 0 && p < static_cast<int>(body.parts.size()),
                     "simulation: dressing names body part " << p << ", the body has " << body.parts.size());
  if (newton_) {
    // The Newton path's barrier keeps a vertex off the parts its own meets as well, so that it cannot enter a part
    // through the opening where the next one begins.
    newton_->setColliders(std::move(colliders), dressing.part, body::meetingParts(body.parts));
  } else
    solver_->setColliders(std::move(colliders), dressing.part);

  // Pins keep their dressed offsets from the body.
  const garment::EmbeddedFrames frames = garment::embeddedFrames(body.mesh.V, body.mesh.F, dressing.embedding);
  const Eigen::MatrixX3d offsets = garment::offsetsFromPositions(frames, dressing.relaxed);
  const int pins = static_cast<int>(options_.pinned.size());
  restOffsets_.resize(pins, 3);
  pinEmbedding_.triangle.resize(pins);
  pinEmbedding_.barycentric.resize(pins, 3);
  pinEmbedding_.tangentCoords.resize(pins, 2);
  for (int k = 0; k < pins; ++k) {
    const int v = options_.pinned[k];
    restOffsets_.row(k) = offsets.row(v);
    pinEmbedding_.triangle(k) = dressing.embedding.triangle(v);
    pinEmbedding_.barycentric.row(k) = dressing.embedding.barycentric.row(v);
    pinEmbedding_.tangentCoords.row(k) = dressing.embedding.tangentCoords.row(v);
  }

  // Settle the dressed garment under gravity in the rest pose; every pose starts from here.
  const auto start = std::chrono::steady_clock::now();
  placeBody(body::Pose::identity());
  rest_ = settled ? *settled : dressing.relaxed;
  PIXELCLOTH_CHECK(rest_.rows() == n, "simulation: the settled garment has " << rest_.rows() << " vertices, not " << n);
  if (newton_) {
    EquilibriumReport report;
    if (!settled) {
      // Frictionless: the dressing's leftover compression relaxes instead of sticking to the body.
      newton_->setFriction(0);
      newton_->beginStep(rest_);
      report = newton_->solve(rest_, options_.newton.restIterations);
      newton_->setFriction(options_.newton.solver.friction);
      restSettled_ = report.converged;
    }
    restStats_ = measure(rest_);
    restStats_.iterations = report.iterations;
    restStats_.residual = report.lastMove;
    recordForce(restStats_, rest_);
  } else {
    RelaxReport report;
    if (!settled) {
      // Frictionless: the dressing's leftover compression relaxes instead of sticking to the body.
      solver_->setFriction(0);
      report = solver_->relax(rest_, options_.restIterations);
      solver_->setFriction(options_.solver.friction);
      restSettled_ = report.converged;
    }
    // Springs on the contacts of the settled drape, for good: no refactoring per sample, and every simulator built
    // from the same drape (one per thread) gives the same sample for the same pose.
    solver_->freezeContactSprings(rest_);
    restStats_ = measure(rest_);
    restStats_.iterations = report.iterations;
    restStats_.residual = report.residual;
  }
  restStats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  PIXELCLOTH_CHECK(rest_.allFinite(), "simulation: the garment did not settle in the rest pose (not finite)");
}

GarmentSimulator::~GarmentSimulator() = default;

void GarmentSimulator::placeBody(const body::Pose& pose) {
  posedBody_ = body_.posedVertices(pose);
  std::vector<Eigen::MatrixX3d> placed;
  for (const std::vector<int>& vertices : partVertices_) {
    Eigen::MatrixX3d V(static_cast<int>(vertices.size()), 3);
    for (size_t i = 0; i < vertices.size(); ++i) V.row(static_cast<int>(i)) = posedBody_.row(vertices[i]);
    placed.push_back(std::move(V));
  }
  if (newton_)
    newton_->moveColliders(placed);
  else
    solver_->moveColliders(placed);
  if (!options_.pinned.empty()) {
    const garment::EmbeddedFrames frames = garment::embeddedFrames(posedBody_, body_.mesh.F, pinEmbedding_);
    const Eigen::MatrixX3d targets = garment::positionsFromOffsets(frames, restOffsets_);
    if (newton_)
      newton_->setPinTargets(targets);
    else
      solver_->setPinTargets(targets);
  }
}

data::SampleStats GarmentSimulator::measure(const Eigen::MatrixX3d& x) const {
  data::SampleStats stats;
  if (!x.allFinite()) {
    stats.rejection = data::Rejection::NotFinite;
    return stats;
  }
  const Eigen::VectorXd ratio = newton_ ? newton_->areaRatios(x) : solver_->areaRatios(x);
  stats.minAreaRatio = ratio.minCoeff();
  stats.maxAreaRatio = ratio.maxCoeff();
  stats.maxPenetration =
      newton_ ? std::max(0.0, -newton_->distances(x).minCoeff()) : solver_->penetration(x).maxCoeff();
  if (stats.minAreaRatio < options_.minAreaRatio)
    stats.rejection = data::Rejection::TriangleShrank;
  else if (stats.maxAreaRatio > options_.maxAreaRatio)
    stats.rejection = data::Rejection::TriangleGrew;
  else if (stats.maxPenetration > options_.maxPenetration)
    stats.rejection = data::Rejection::Penetrated;
  return stats;
}

double GarmentSimulator::coulombRatio(const Eigen::MatrixX3d& x) const {
  return x.allFinite() ? newton_->coulombExcess(x).cwiseQuotient(newton_->weights()).maxCoeff() : 0.0;
}

void GarmentSimulator::recordForce(data::SampleStats& stats, const Eigen::MatrixX3d& x) const {
  if (!newton_ || !x.allFinite()) return;
  const Eigen::VectorXd force = newton_->forces(x).rowwise().norm();
  stats.maxResidualForce = force.maxCoeff();
  stats.residualForceRatio = force.cwiseQuotient(newton_->weights()).maxCoeff();
}

void GarmentSimulator::rideAlong(Eigen::MatrixX3d& x, const body::Pose& pose) {
  // The cloth rides with the body to the next pose (constant offsets in the embedded frames), so the solver only
  // relaxes what skinning gets wrong instead of having the arms drag the sleeves through contact. The Newton path
  // embeds each vertex afresh at the closest point of its own body part: a vertex that slid centimetres from where
  // it was dressed would otherwise swing with a frame there, and skinning bends the skin around the shoulder enough
  // between the two to carry it through its part's surface.
  garment::Embedding embedding = dressing_.embedding;
  if (newton_) {
    Eigen::VectorXi face;
    Eigen::MatrixX3d barycentric;
    newton_->closestPoints(x, face, barycentric);
    for (int v = 0; v < x.rows(); ++v) {
      if (face(v) < 0) continue;
      embedding.triangle(v) = body_.parts[dressing_.part[v]].faces[face(v)];
      embedding.barycentric.row(v) = barycentric.row(v);
      embedding.tangentCoords.row(v) = Eigen::RowVector2d(1, 0);  // along the face's first edge: any will do
    }
  }
  const Eigen::MatrixX3d offsets =
      garment::offsetsFromPositions(garment::embeddedFrames(posedBody_, body_.mesh.F, embedding), x);
  placeBody(pose);
  x = garment::positionsFromOffsets(garment::embeddedFrames(posedBody_, body_.mesh.F, embedding), offsets);
}

data::Sample GarmentSimulator::simulate(const body::Pose& pose) {
  const auto start = std::chrono::steady_clock::now();
  const double stepDegrees = newton_ ? options_.newton.stepDegrees : options_.stepDegrees;
  const int steps = std::max(1, static_cast<int>(std::ceil(largestJointAngle(pose) / stepDegrees)));
  Eigen::MatrixX3d x = rest_;
  data::Sample sample;
  if (newton_) {
    sample.stats = simulateNewton(pose, steps, x);
  } else {
    sample.stats = simulateProjective(pose, steps, x);
  }
  sample.pose = pose.toVector();
  sample.pose = sample.pose.head(garment_.traits.poseSize()).eval();
  sample.positions = x.cast<float>();
  if (sample.stats.rejection != data::Rejection::NotFinite) {
    const garment::EmbeddedFrames frames = garment::embeddedFrames(posedBody_, body_.mesh.F, dressing_.embedding);
    sample.offsets = garment::offsetsFromPositions(frames, x).cast<float>();
  } else {
    sample.offsets = Eigen::MatrixX3f::Constant(x.rows(), 3, std::nanf(""));
  }
  sample.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sample;
}

data::SampleStats GarmentSimulator::simulateNewton(const body::Pose& pose, int steps, Eigen::MatrixX3d& x) {
  const NewtonSchedule& schedule = options_.newton;
  int iterations = 0;
  EquilibriumReport report;
  placeBody(body::Pose::identity());
  for (int step = 1; step <= steps; ++step) {
    rideAlong(x, partialPose(pose, static_cast<double>(step) / steps));
    newton_->beginStep(x);  // friction lagged where the step starts
    if (step < steps) {
      iterations += newton_->solve(x, schedule.iterationsPerStep, schedule.stepTolerance).iterations;
      continue;
    }
    report = newton_->solve(x, schedule.finalIterations);
    iterations += report.iterations;
    // Friction lagged at the step's start may hold vertices whose contact has since let go or eased: ease it where
    // the cloth now is (never raising it) and solve again, until every contact's friction is within its Coulomb
    // bound (IPC's lagged iterations, made monotone).
    for (int lag = 0;
         lag < schedule.frictionLags && report.converged && coulombRatio(x) >= schedule.solver.forceTolerance; ++lag) {
      newton_->updateFriction(x, schedule.frictionEase);
      report = newton_->solve(x, schedule.finalIterations);
      iterations += report.iterations;
    }
  }
  data::SampleStats stats = measure(x);
  // The stopping measure: the largest net force on a vertex, friction beyond its Coulomb bound counted as unbalanced.
  const double excess = coulombRatio(x);
  const bool converged = report.converged && excess < schedule.solver.forceTolerance;
  if (stats.rejection == data::Rejection::None && !converged) stats.rejection = data::Rejection::NotConverged;
  stats.iterations = iterations;
  stats.residual = report.lastMove;
  stats.maxResidualForce = report.maxForce;
  stats.residualForceRatio = std::max(report.maxForceRatio, excess);
  return stats;
}

data::SampleStats GarmentSimulator::simulateProjective(const body::Pose& pose, int steps, Eigen::MatrixX3d& x) {
  int iterations = 0;
  RelaxReport report;
  placeBody(body::Pose::identity());
  for (int step = 1; step <= steps && x.allFinite(); ++step) {
    rideAlong(x, partialPose(pose, static_cast<double>(step) / steps));
    if (step == steps) solver_->setContactRecheckEvery(options_.finalRecheckEvery);
    report = solver_->relax(x, step < steps ? options_.iterationsPerStep : options_.finalIterations);
    iterations += report.iterations;
  }
  data::SampleStats stats = measure(x);
  // Not there yet: relax on from where it is (SimulationOptions::extraIterations).
  int rounds = 0;
  for (int extra = 0; extra < options_.extraIterations && stats.rejection != data::Rejection::None &&
                      stats.rejection != data::Rejection::NotFinite;
       extra += options_.extraRound, ++rounds) {
    report = solver_->relax(x, std::min(options_.extraRound, options_.extraIterations - extra));
    iterations += report.iterations;
    stats = measure(x);
  }
  solver_->setContactRecheckEvery(options_.solver.contactRecheckEvery);
  stats.iterations = iterations;
  stats.extraRounds = rounds;
  stats.residual = report.residual;
  return stats;
}

}  // namespace pixelcloth::sim
