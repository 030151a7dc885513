#include "backend/gyro_stillness.h"

#include <cmath>

namespace uwbsar {

namespace {
constexpr double kRadPerDeg = M_PI / 180.0;
}  // namespace

GyroStillness::GyroStillness(const BackendConfig& config)
    : min_still_s_(config.gyro_still_min_s),
      noise_density_radps_per_sqrt_hz_(config.gyro_rate_noise_dps_per_sqrt_hz * kRadPerDeg) {}

std::optional<GyroStandstill> GyroStillness::Add(double t_s, const Pose2& T_world_robot) {
  if (!std::isfinite(t_s) || (has_last_ && t_s <= last_t_s_)) return std::nullopt;
  std::optional<GyroStandstill> ended;
  if (has_last_) {
    const double dt_s = t_s - last_t_s_;
    const double travel_m =
        std::hypot(T_world_robot.x_m - last_.x_m, T_world_robot.y_m - last_.y_m);
    const double turn_rad = NormalizeAngle(T_world_robot.yaw_rad - last_.yaw_rad);
    const bool still = dt_s <= kMaxStillStepS && travel_m < kMaxStillStepM &&
                       std::abs(turn_rad) < kMaxStillRateDps * kRadPerDeg * dt_s;
    if (still) {
      if (!still_) {
        still_ = true;
        still_begin_s_ = last_t_s_;
        still_turn_rad_ = 0.0;
      }
      still_turn_rad_ += turn_rad;
    } else {
      ended = Close();
    }
  }
  has_last_ = true;
  last_t_s_ = t_s;
  last_ = T_world_robot;
  return ended;
}

std::optional<GyroStandstill> GyroStillness::Close() {
  if (!still_) return std::nullopt;
  still_ = false;
  const double duration_s = last_t_s_ - still_begin_s_;
  if (duration_s < min_still_s_) return std::nullopt;
  GyroStandstill s;
  s.begin_s = still_begin_s_;
  s.end_s = last_t_s_;
  s.bias_radps = still_turn_rad_ / duration_s;
  s.sigma_radps = noise_density_radps_per_sqrt_hz_ / std::sqrt(duration_s);
  return s;
}

std::optional<GyroStandstill> GyroStillness::Flush() {
  std::optional<GyroStandstill> s = Close();
  has_last_ = false;
  return s;
}

}  // namespace uwbsar
