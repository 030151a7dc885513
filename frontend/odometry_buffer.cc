#include "frontend/odometry_buffer.h"

#include <algorithm>
#include <cmath>

namespace uwbsar {

bool OdometryBuffer::Plausible(const OdometrySample& a, const OdometrySample& b) const {
  const double dt_s = std::max(NsToSeconds(b.stamp_ns - a.stamp_ns), kMinSpeedWindowS);
  const double step_m = Distance(a.T_world_robot, b.T_world_robot);
  const double turn_rad =
      std::abs(NormalizeAngle(b.T_world_robot.yaw_rad - a.T_world_robot.yaw_rad));
  // Written so that an overflow to Inf or a NaN counts as implausible.
  return step_m <= config_.max_odom_speed_mps * dt_s &&
         turn_rad <= config_.max_odom_turn_rate_radps * dt_s;
}

bool OdometryBuffer::Append(const OdometrySample& sample, bool jump) {
  const Pose2& raw = sample.T_world_robot;
  jump = jump || (last_raw_ && Distance(last_raw_->T_world_robot, raw) > config_.max_odom_jump_m);
  if (jump) {
    // Re-anchor: the corrected pose continues from where the robot was.
    T_corrected_raw_ = entries_.back().T_world_robot * raw.Inverse();
    jump = true;
  }
  last_raw_ = sample;
  OdometryEntry entry;
  entry.stamp_ns = sample.stamp_ns;
  entry.T_world_robot = T_corrected_raw_ * raw;
  entry.path_m = entries_.empty() ? 0.0
                                  : entries_.back().path_m + Distance(entries_.back().T_world_robot,
                                                                      entry.T_world_robot);
  entries_.push_back(entry);
  return jump;
}

OdometryBuffer::AddReport OdometryBuffer::Add(const OdometrySample& sample) {
  AddReport report;
  const Pose2& raw = sample.T_world_robot;
  if (!std::isfinite(raw.x_m) || !std::isfinite(raw.y_m) || !std::isfinite(raw.yaw_rad) ||
      std::abs(raw.x_m) > kMaxOdomCoordinateM || std::abs(raw.y_m) > kMaxOdomCoordinateM) {
    report.result = AddResult::kNonFinite;
    return report;
  }
  const TimestampNs newest =
      held_ ? held_->stamp_ns : (entries_.empty() ? 0 : entries_.back().stamp_ns);
  if ((!entries_.empty() || held_) && sample.stamp_ns <= newest) {
    report.result = AddResult::kOutOfOrder;
    return report;
  }
  if (last_raw_ && !Plausible(*last_raw_, sample)) {
    if (held_ && Plausible(*held_, sample)) {
      // The held sample and this one agree: the odometry did move (a reset). Keep both.
      report.jumps += Append(*held_, /*jump=*/true);
      report.jumps += Append(sample, false);
      report.appended = 2;
      held_.reset();
      return report;
    }
    // Impossible from the last accepted sample: wait for the next one to decide.
    report.outlier_dropped = held_.has_value();
    held_ = sample;
    report.result = AddResult::kHeld;
    return report;
  }
  // Plausible from the last accepted sample: a held sample in between was an outlier.
  report.outlier_dropped = held_.has_value();
  held_.reset();
  report.jumps += Append(sample, false);
  report.appended = 1;
  return report;
}

bool OdometryBuffer::DropHeld() {
  const bool had = held_.has_value();
  held_.reset();
  return had;
}

OdometryBuffer::LookupResult OdometryBuffer::Lookup(TimestampNs stamp_ns,
                                                    OdometryEntry* out) const {
  if (entries_.empty() || stamp_ns < entries_.front().stamp_ns) return LookupResult::kBeforeFirst;
  if (stamp_ns > entries_.back().stamp_ns) return LookupResult::kAfterLast;
  auto after =
      std::lower_bound(entries_.begin(), entries_.end(), stamp_ns,
                       [](const OdometryEntry& e, TimestampNs t) { return e.stamp_ns < t; });
  if (after->stamp_ns == stamp_ns) {
    *out = *after;
    return LookupResult::kOk;
  }
  const OdometryEntry& b = *after;
  const OdometryEntry& a = *(after - 1);
  if (NsToSeconds(b.stamp_ns - a.stamp_ns) > config_.max_odom_gap_s) return LookupResult::kGap;
  const double t =
      static_cast<double>(stamp_ns - a.stamp_ns) / static_cast<double>(b.stamp_ns - a.stamp_ns);
  out->stamp_ns = stamp_ns;
  out->T_world_robot = Interpolate(a.T_world_robot, b.T_world_robot, t);
  out->path_m = a.path_m + t * (b.path_m - a.path_m);
  return LookupResult::kOk;
}

void OdometryBuffer::TrimBefore(TimestampNs stamp_ns) {
  while (entries_.size() > 2 && entries_[1].stamp_ns < stamp_ns) entries_.pop_front();
}

}  // namespace uwbsar
