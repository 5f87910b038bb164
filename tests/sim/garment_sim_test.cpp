// The T-shirt simulated on the mannequin: the continuation carries the sleeves with the arms, contacts keep the
// cloth out of each vertex's body part, and a sample depends only on its pose.
#include "pixelcloth/sim/garment_sim.h"

#include <gtest/gtest.h>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/garment_cage.h"
#include "support/test_util.h"

namespace pixelcloth::sim {
namespace {

class TShirtSimulation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    body_ = new body::Body(body::makeMannequin());
    shirt_ = new garment::Garment(garment::makeTShirt());
    dressing_ =
        new cage::Dressing(cage::dressGarment(*body_, cage::bodyCage(*body_), *shirt_, cage::garmentCage(*shirt_)));
    simulator_ = new GarmentSimulator(*body_, *shirt_, *dressing_);
  }
  static void TearDownTestSuite() {
    delete simulator_;
    delete dressing_;
    delete shirt_;
    delete body_;
  }
  /// Both arms lowered by `degrees` at the shoulder joints (about the body's forward axis), the spine bent forward.
  static body::Pose armsDown(double degrees) {
    Eigen::Matrix<double, 10, 3> euler = Eigen::Matrix<double, 10, 3>::Zero();
    euler(1, 0) = 15;        // spine: bend forward
    euler(5, 2) = -degrees;  // l_arm
    euler(8, 2) = degrees;   // r_arm
    return body::Pose::fromEulerDegrees(euler);
  }
  static body::Body* body_;
  static garment::Garment* shirt_;
  static cage::Dressing* dressing_;
  static GarmentSimulator* simulator_;
};
body::Body* TShirtSimulation::body_ = nullptr;
garment::Garment* TShirtSimulation::shirt_ = nullptr;
cage::Dressing* TShirtSimulation::dressing_ = nullptr;
GarmentSimulator* TShirtSimulation::simulator_ = nullptr;

TEST_F(TShirtSimulation, RestDrapeSettlesWithoutDistortionOrPenetration) {
  const data::SampleStats& rest = simulator_->restStats();
  EXPECT_EQ(rest.rejection, data::Rejection::None);
  EXPECT_LT(rest.residual, 1e-4);
  EXPECT_LT(rest.maxPenetration, 0.002);
  EXPECT_GT(rest.minAreaRatio, 0.7);
  EXPECT_LT(rest.maxAreaRatio, 1.6);
  EXPECT_TRUE(simulator_->restSettled());
}

TEST_F(TShirtSimulation, ARestSettleStoppedAtItsCapIsNotSettled) {
  SimulationOptions options;
  options.restIterations = 2;
  const GarmentSimulator capped(*body_, *shirt_, *dressing_, options);
  EXPECT_EQ(capped.restStats().iterations, 2);
  EXPECT_FALSE(capped.restSettled());
}

TEST(SimulationOptions, ExtraRoundsAndRechecksOutOfRangeAreRefused) {
  SimulationOptions negative;
  negative.extraIterations = -1;
  EXPECT_NE(testing::inputErrorOf([&] { negative.validate(); }).find("extra iterations >= 0"), std::string::npos);
  SimulationOptions emptyRound;
  emptyRound.extraRound = 0;
  EXPECT_NE(testing::inputErrorOf([&] { emptyRound.validate(); }).find("extra round >= 1"), std::string::npos);
  SimulationOptions noRecheck;
  noRecheck.finalRecheckEvery = 0;
  EXPECT_NE(testing::inputErrorOf([&] { noRecheck.validate(); }).find("final recheck interval"), std::string::npos);
  SimulationOptions off;
  off.extraIterations = 0;  // turns the extra rounds off: valid
  EXPECT_NO_THROW(off.validate());
}

TEST_F(TShirtSimulation, LoweredArmsCarryTheirSleevesAndASampleDependsOnlyOnItsPose) {
  const data::Sample first = simulator_->simulate(armsDown(40));
  ASSERT_TRUE(first.positions.allFinite());
  EXPECT_EQ(first.stats.rejection, data::Rejection::None) << data::rejectionName(first.stats.rejection);
  EXPECT_LT(first.stats.maxPenetration, 0.002);
  EXPECT_GT(first.stats.minAreaRatio, 0.25);
  EXPECT_LT(first.stats.maxAreaRatio, 2.0);
  // The sleeves went down with the arms: the lowest sleeve hem vertex is well below where it hung at rest.
  double restLowest = 1e9, posedLowest = 1e9;
  for (int v = 0; v < shirt_->mesh.numVertices(); ++v)
    if (body_->parts[dressing_->part[v]].name != "torso") {  // a sleeve vertex (collides with an arm)
      restLowest = std::min(restLowest, simulator_->restDrape()(v, 1));
      posedLowest = std::min(posedLowest, static_cast<double>(first.positions(v, 1)));
    }
  EXPECT_LT(posedLowest, restLowest - 0.05);
  // Another pose in between changes nothing: the same pose gives the same shirt.
  simulator_->simulate(armsDown(-30));
  const data::Sample again = simulator_->simulate(armsDown(40));
  EXPECT_EQ((again.positions - first.positions).cwiseAbs().maxCoeff(), 0.0f);
  // Nor does the simulator: another one built from the same settled drape (as each generate thread is).
  GarmentSimulator other(*body_, *shirt_, *dressing_, {}, &simulator_->restDrape());
  EXPECT_EQ((other.simulate(armsDown(40)).positions - first.positions).cwiseAbs().maxCoeff(), 0.0f);
}

// The Newton solver (SolverKind::Newton) on a coarser T-shirt of the same pattern, so that its factorisations stay
// cheap, and a pose that bends forward with both arms lowered.
class NewtonSimulation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    body_ = new body::Body(body::makeMannequin());
    garment::TShirtOptions coarse;
    coarse.targetVertices = 1000;
    shirt_ = new garment::Garment(garment::makeTShirt(coarse));
    dressing_ =
        new cage::Dressing(cage::dressGarment(*body_, cage::bodyCage(*body_), *shirt_, cage::garmentCage(*shirt_)));
  }
  static void TearDownTestSuite() {
    delete dressing_;
    delete shirt_;
    delete body_;
  }
  static Eigen::Matrix<double, 10, 3> leanArmsDown() {
    Eigen::Matrix<double, 10, 3> euler = Eigen::Matrix<double, 10, 3>::Zero();
    euler(1, 0) = 10;   // spine: bend forward
    euler(5, 2) = -30;  // l_arm down
    euler(8, 2) = 30;   // r_arm down
    return euler;
  }
  static body::Body* body_;
  static garment::Garment* shirt_;
  static cage::Dressing* dressing_;
};
body::Body* NewtonSimulation::body_ = nullptr;
garment::Garment* NewtonSimulation::shirt_ = nullptr;
cage::Dressing* NewtonSimulation::dressing_ = nullptr;

// The rest drape and a kept pose are static equilibria, checked against the net force recomputed here; a pose that
// cannot get there within its budget is rejected as not converged, never kept.
TEST_F(NewtonSimulation, RestDrapeAndAKeptPoseAreEquilibriaAndAnUnfinishedOneIsRejected) {
  const body::Body& body = *body_;
  const garment::Garment& shirt = *shirt_;
  const cage::Dressing& dressing = *dressing_;
  SimulationOptions options;
  options.kind = SolverKind::Newton;
  GarmentSimulator simulator(body, shirt, dressing, options);
  const double tolerance = options.newton.solver.forceTolerance;
  EXPECT_TRUE(simulator.restSettled());
  EXPECT_LT(simulator.restStats().residualForceRatio, tolerance);
  EXPECT_EQ(simulator.restStats().maxPenetration, 0.0);  // the barrier keeps every vertex outside

  const Eigen::Matrix<double, 10, 3> euler = leanArmsDown();
  const body::Pose pose = body::Pose::fromEulerDegrees(euler);
  const data::Sample sample = simulator.simulate(pose);
  ASSERT_EQ(sample.stats.rejection, data::Rejection::None)
      << data::rejectionName(sample.stats.rejection) << ", " << sample.stats.residualForceRatio << " of the weight";
  EXPECT_LT(sample.stats.residualForceRatio, tolerance);
  EXPECT_GT(sample.stats.maxResidualForce, 0.0);
  EXPECT_EQ(sample.stats.maxPenetration, 0.0);
  // The same measure from a solver of our own, with the body placed in the pose: on every vertex out of the
  // barrier's reach (no contact, no friction) the net force of stretch, bending and gravity is within the tolerance.
  EquilibriumSolver check(shirt.mesh, {}, options.newton.solver);
  std::vector<Collider> colliders;
  const Eigen::MatrixX3d posed = body.posedVertices(pose);
  for (const body::BodyPart& part : body.parts) {
    Collider collider;
    collider.V = posed;
    collider.F.resize(static_cast<int>(part.faces.size()), 3);
    for (size_t f = 0; f < part.faces.size(); ++f) collider.F.row(static_cast<int>(f)) = body.mesh.F.row(part.faces[f]);
    colliders.push_back(std::move(collider));
  }
  check.setColliders(std::move(colliders), dressing.part, body::meetingParts(body.parts));
  check.setFriction(0);
  const Eigen::MatrixX3d x = sample.positions.cast<double>();
  const Eigen::VectorXd ratio = check.forces(x).rowwise().norm().cwiseQuotient(check.weights());
  const Eigen::VectorXd distance = check.clearances(x);
  int free = 0;
  for (int v = 0; v < x.rows(); ++v)
    if (distance(v) > 1.5 * options.newton.solver.barrierDistance) {
      ++free;
      // Positions are stored as floats: their rounding (0.1 um at 1.5 m) strains the 60 N/m membrane by 3e-6,
      // about 1 to 2% of a vertex's weight on this mesh.
      EXPECT_LT(ratio(v), 4 * tolerance) << "vertex " << v << " at " << distance(v) << " m";
    }
  EXPECT_GT(free, x.rows() / 4);

  // The same pose again, after another one: the same shirt.
  simulator.simulate(body::Pose::fromEulerDegrees(-euler));
  EXPECT_EQ((simulator.simulate(pose).positions - sample.positions).cwiseAbs().maxCoeff(), 0.0f);

  // Two Newton iterations at the target pose are not enough: rejected, never kept half-way.
  SimulationOptions hurried = options;
  hurried.newton.finalIterations = 2;
  GarmentSimulator quick(body, shirt, dressing, hurried, &simulator.restDrape());
  const data::Sample unfinished = quick.simulate(pose);
  EXPECT_EQ(unfinished.stats.rejection, data::Rejection::NotConverged);
  EXPECT_GT(unfinished.stats.residualForceRatio, tolerance);
}

// With Coulomb friction (mu = 0.3) the friction lagged where the last continuation step starts holds cloth whose
// contact has since eased or let go; the lags at the target pose ease it until every contact's friction is within
// mu times the normal force that holds it. Without them the pose is rejected, never kept with friction no contact
// provides.
TEST_F(NewtonSimulation, FrictionIsEasedWithinTheCoulombBoundAndAPoseBeyondItIsRejected) {
  SimulationOptions options;
  options.kind = SolverKind::Newton;
  GarmentSimulator frictionless(*body_, *shirt_, *dressing_, options);
  options.newton.solver.friction = 0.3;
  GarmentSimulator simulator(*body_, *shirt_, *dressing_, options, &frictionless.restDrape());
  const double tolerance = options.newton.solver.forceTolerance;
  const body::Pose pose = body::Pose::fromEulerDegrees(leanArmsDown());
  const data::Sample held = simulator.simulate(pose);
  ASSERT_EQ(held.stats.rejection, data::Rejection::None)
      << data::rejectionName(held.stats.rejection) << ", " << held.stats.residualForceRatio << " of the weight";
  EXPECT_LT(held.stats.residualForceRatio, tolerance);  // net force and friction beyond the bound, both
  // Friction holds the shirt elsewhere than where it slides to without.
  const data::Sample slid = frictionless.simulate(pose);
  ASSERT_EQ(slid.stats.rejection, data::Rejection::None);
  EXPECT_GT((held.positions - slid.positions).rowwise().norm().mean(), 1e-3f);

  // No lags: the friction lagged at the last step's start is left beyond the bound, and the pose is rejected.
  SimulationOptions unlagged = options;
  unlagged.newton.frictionLags = 0;
  GarmentSimulator hasty(*body_, *shirt_, *dressing_, unlagged, &frictionless.restDrape());
  const data::Sample unfinished = hasty.simulate(pose);
  EXPECT_EQ(unfinished.stats.rejection, data::Rejection::NotConverged);
  EXPECT_GT(unfinished.stats.residualForceRatio, tolerance);
}

TEST(SimulationOptions, SolverNamesAndNewtonScheduleOutOfRangeAreRefused) {
  EXPECT_EQ(parseSolverKind("newton", "test"), SolverKind::Newton);
  EXPECT_EQ(parseSolverKind("pd", "test"), SolverKind::ProjectiveDynamics);
  EXPECT_NE(testing::inputErrorOf([] { parseSolverKind("ipc", "generate --solver"); }).find("expected pd or newton"),
            std::string::npos);
  SimulationOptions options;
  options.kind = SolverKind::Newton;
  options.newton.frictionLags = -1;
  EXPECT_NE(testing::inputErrorOf([&] { options.validate(); }).find("friction lags"), std::string::npos);
  options.newton.frictionLags = 0;
  options.newton.frictionEase = 0;
  EXPECT_NE(testing::inputErrorOf([&] { options.validate(); }).find("friction ease"), std::string::npos);
  options.newton.frictionEase = 0.7;
  options.newton.stepTolerance = 0;
  EXPECT_NE(testing::inputErrorOf([&] { options.validate(); }).find("step tolerance"), std::string::npos);
  options.newton.stepTolerance = 0.2;
  options.newton.stepDegrees = 0;
  EXPECT_NE(testing::inputErrorOf([&] { options.validate(); }).find("step must be in (0, 180] degrees"),
            std::string::npos);
}

}  // namespace
}  // namespace pixelcloth::sim
