// A simulated run's gyro bias as the backend estimated it (backend.odometry_model gyro:
// PoseGraph::GyroBiases, one value per segment) against the simulator's true bias
// (drivers/sim/sim_stream.h TrueGyroBiasRadps, replayed from the run's seed): the turn-on bias,
// the mean over the run and the error of each segment's estimate at the segment's middle.
#pragma once

#include <cstdint>
#include <string>

#include "slam/app_config.h"
#include "slam/map_job.h"

namespace uwbsar::eval {

struct GyroBiasEvaluation {
  int segments = 0;  ///< the run's bias segments (0: no gyro bias estimated, or no gyro)
  double true_turn_on_radps = 0.0;    ///< the bias the gyro started with
  double first_estimate_radps = 0.0;  ///< the estimate of the segment holding the start
  double true_mean_radps = 0.0;       ///< over the run (segments weighted by their time in it)
  double estimated_mean_radps = 0.0;  ///< ... the estimates
  double rms_error_radps = 0.0;       ///< each segment's estimate against the truth at its middle
};

/// The evaluation of trajectory 0 of `run`, mapped from the simulation of `config` and `seed`.
GyroBiasEvaluation EvaluateGyroBias(const slam::MapRun& run, const Config& config,
                                    std::uint64_t seed);

/// One line, in deg/s.
std::string FormatGyroBiasEvaluation(const GyroBiasEvaluation& e);

}  // namespace uwbsar::eval
