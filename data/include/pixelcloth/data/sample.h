#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>

namespace pixelcloth::data {

/// Why a drawn sample was discarded: the pose sampler pruned it (an arm inside the torso), or the simulation failed
/// the paper's test (a triangle shrank by more than 75% or grew by more than 100%), ended with cloth inside its body
/// part deeper than allowed, did not stay finite, or (Newton solver) did not reach static equilibrium: the largest
/// net force on a vertex stayed above the solver's tolerance.
enum class Rejection { None, TriangleShrank, TriangleGrew, NotFinite, ArmInsideTorso, Penetrated, NotConverged };

/// "none", "triangle_shrank", "triangle_grew", "not_finite", "arm_inside_torso", "penetrated", "not_converged".
const char* rejectionName(Rejection rejection);

/// What the quasistatic solver reports for one pose.
struct SampleStats {
  int iterations = 0;         ///< solver iterations over all continuation steps
  int extraRounds = 0;        ///< rounds relaxed past the scheduled iterations (sim::SimulationOptions::extraIterations)
  double residual = 0;        ///< largest vertex move in the last iteration (metres)
  /// Largest net force on a vertex at the end (newtons) and the same over that vertex's weight, the Newton solver's
  /// stopping measure; NaN when not measured (the projective-dynamics solver).
  double maxResidualForce = std::numeric_limits<double>::quiet_NaN();
  double residualForceRatio = std::numeric_limits<double>::quiet_NaN();
  double maxPenetration = 0;  ///< deepest cloth vertex inside its collision part (metres, >= 0)
  double minAreaRatio = 1;    ///< smallest triangle area over its pattern (rest) area
  double maxAreaRatio = 1;    ///< largest such ratio
  double seconds = 0;         ///< wall time of the solve
  Rejection rejection = Rejection::None;
};

/// One simulated (or imported) sample: the pose and the garment's shape.
struct Sample {
  Eigen::VectorXf pose;        ///< 90 floats (T-shirt) or the first 36 (necktie), body::Pose::toVector order
  Eigen::MatrixX3f positions;  ///< #V x 3 world positions (metres)
  Eigen::MatrixX3f offsets;    ///< #V x 3 offsets (du, dv, dn) in the embedded frames of the posed body
  SampleStats stats;
};

}  // namespace pixelcloth::data
