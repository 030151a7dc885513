// A run's gyro bias as a state of the pose graph (backend.odometry_model: gyro). A yaw gyro's
// bias is set at each power-up (the turn-on bias) and then wanders (its random walk); the
// base integrates it into the heading over time. It belongs to the run, never to the robot,
// so it is estimated online, like the poses:
//  - piecewise constant over segments of gyro_bias_segment_s (absolute time: segment k covers
//    [k T, (k + 1) T)); each calibrated odometry edge reads the segment of its middle;
//  - consecutive segments are tied by the walk: r = (b_k+1 - b_k) / (K sqrt(T)), K the
//    walk's density (gyro_bias_walk_dps_per_sqrt_s); with K = 0 the run has one segment;
//  - the first segment made carries the turn-on prior r = b / gyro_bias_sigma_dps;
//  - a standstill measures the bias directly (backend/gyro_stillness.h): r = (b - z) / sigma_z
//    on the segment it falls in.
// Loops, wall edges and landmarks then observe it through the odometry edges. The segments are
// made on demand, contiguous from the first to the last, so every pair of neighbours is tied.
#pragma once

#include <ceres/problem.h>

#include <map>
#include <memory>
#include <vector>

#include "backend/backend_config.h"

namespace uwbsar {

class GyroBiasTrack {
 public:
  /// Adds its blocks and residuals to `problem` (not owned; must outlive the track).
  GyroBiasTrack(ceres::Problem* problem, const BackendConfig& config);

  /// The bias block (1 value, rad/s) of the segment holding time `t_s`; makes the segments
  /// between the track's ends and it.
  double* BlockAt(double t_s);
  /// A direct measurement of the bias at `t_s` (a standstill): `bias_radps` +- `sigma_radps`.
  void AddMeasurement(double t_s, double bias_radps, double sigma_radps);

  /// The sum of the prior, walk and measurement residuals squared at the current state.
  double Chi2() const;
  /// The segments' values in time order, and back (trial solves restore a refused map).
  std::vector<double> State() const;
  void Restore(const std::vector<double>& state);
  /// The bias of the latest segment (0 before any), rad/s.
  double Latest() const;
  /// Each segment's start time (s) and bias (rad/s), in time order.
  std::vector<std::pair<double, double>> Segments() const;

 private:
  struct Term {
    double* a = nullptr;
    double* b = nullptr;  ///< walks only
    double mean = 0.0;    ///< priors and measurements
    double sigma = 1.0;
  };
  long long SegmentOf(double t_s) const;
  double* MakeSegment(long long k);

  ceres::Problem* problem_;
  double segment_s_;
  double walk_sigma_radps_;  ///< between neighbours: K sqrt(T)
  double turn_on_sigma_radps_;
  std::map<long long, std::unique_ptr<double>> segments_;
  std::vector<Term> terms_;
};

}  // namespace uwbsar
