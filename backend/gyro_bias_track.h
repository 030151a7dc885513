// A run's gyro bias as a state of the pose graph (backend.odometry_model: gyro). A yaw gyro's
// bias is set at each power-up (the turn-on bias) and then wanders (its random walk); the
// base integrates it into the heading over time. It belongs to the run, never to the robot,
// so it is estimated online, like the poses:
//  - piecewise constant over segments of gyro_bias_segment_s (absolute time: segment k covers
//    [k T, (k + 1) T)); each calibrated odometry edge reads the segment of its middle;
//  - neighbouring segments k < j are tied by the walk: r = (b_j - b_k) / (K sqrt((j - k) T)),
//    K the walk's density (gyro_bias_walk_dps_per_sqrt_s); with K = 0 the run has one segment;
//  - the first segment made carries the turn-on prior r = b / gyro_bias_sigma_dps;
//  - a standstill measures the bias directly (backend/gyro_stillness.h): r = (b - z) / sigma_z
//    on the segment it falls in.
// Loops, wall edges and landmarks then observe it through the odometry edges. Segments are made
// on demand, only where an edge or a standstill falls (a recording with a stray stamp decades
// away makes two segments, not millions); a segment made between two tied ones takes the place
// of their walk with two.
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

  /// The bias block (1 value, rad/s) of the segment holding time `t_s`, made (and tied to its
  /// neighbours) if new.
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
  struct Prior {  ///< the turn-on prior and the standstills
    double* x = nullptr;
    double mean = 0.0;
    double sigma = 1.0;
  };
  struct Walk {  ///< between a segment and the next one made
    double* a = nullptr;
    double* b = nullptr;
    double sigma = 1.0;
    ceres::ResidualBlockId residual = nullptr;
  };
  long long SegmentOf(double t_s) const;
  void Tie(long long from, long long to);  ///< adds the walk from segment `from` to `to`

  ceres::Problem* problem_;
  double segment_s_;
  double walk_radps_per_sqrt_s_;  ///< K
  double turn_on_sigma_radps_;
  std::map<long long, std::unique_ptr<double>> segments_;
  std::vector<Prior> priors_;
  std::map<long long, Walk> walks_;  ///< by the earlier segment
};

}  // namespace uwbsar
