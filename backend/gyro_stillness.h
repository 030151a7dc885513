// The gyro's bias from standstills, as robots in the field measure it: while the base stands
// still its gyro-integrated heading turns at exactly the bias (plus white noise), so the heading's
// change over a standstill divided by its time measures the bias directly, with a standard
// deviation of N / sqrt(T) for a rate noise density N over T seconds.
//
// A step between two odometry samples is still when the base did not travel (under 0.1 mm), its
// heading turned slower than kMaxStillRateDps (a turn in place is faster; a bias is far slower),
// and the samples are at most kMaxStillStepS apart. A run of still steps lasting at least
// backend.gyro_still_min_s is one standstill, reported when the base moves again (or at Flush).
// Works on any stamped pose stream; a wheel-only base's standstills measure a bias of 0, which its
// model ignores.
#pragma once

#include <optional>
#include <vector>

#include "backend/backend_config.h"
#include "core/pose2.h"

namespace uwbsar {

/// One standstill's measurement of the bias.
struct GyroStandstill {
  double begin_s = 0.0;
  double end_s = 0.0;
  double bias_radps = 0.0;
  double sigma_radps = 0.0;
};

class GyroStillness {
 public:
  /// A heading turning faster than this is a turn, not a bias.
  static constexpr double kMaxStillRateDps = 1.0;
  /// Less travel than this between two samples is standing still.
  static constexpr double kMaxStillStepM = 1e-4;
  /// Samples farther apart than this are a gap in the odometry, not a standstill (nothing says
  /// what the heading did in between): a gap ends a standstill.
  static constexpr double kMaxStillStepS = 1.0;

  explicit GyroStillness(const BackendConfig& config);

  /// The next odometry sample (time in s, strictly increasing; others are ignored). Returns the
  /// standstill that this sample ended, if it was long enough.
  std::optional<GyroStandstill> Add(double t_s, const Pose2& T_world_robot);
  /// The standstill in progress, if long enough (the end of a run); resets.
  std::optional<GyroStandstill> Flush();

 private:
  std::optional<GyroStandstill> Close();

  double min_still_s_;
  double noise_density_radps_per_sqrt_hz_;
  bool has_last_ = false;
  double last_t_s_ = 0.0;
  Pose2 last_;
  bool still_ = false;
  double still_begin_s_ = 0.0;
  double still_turn_rad_ = 0.0;  ///< heading change summed over the still steps (unwrapped)
};

}  // namespace uwbsar
