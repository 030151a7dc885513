#include "frontend/odometry_buffer.h"

#include <algorithm>
#include <cmath>

namespace uwbsar {

OdometryBuffer::AddResult OdometryBuffer::Add(const OdometrySample& sample) {
  const Pose2& raw = sample.T_world_robot;
  if (!std::isfinite(raw.x_m) || !std::isfinite(raw.y_m) || !std::isfinite(raw.yaw_rad)) {
    return AddResult::kNonFinite;
  }
  if (!entries_.empty() && sample.stamp_ns <= entries_.back().stamp_ns) {
    return AddResult::kOutOfOrder;
  }
  AddResult result = AddResult::kAccepted;
  if (last_raw_ && Distance(*last_raw_, raw) > config_.max_odom_jump_m) {
    // Re-anchor: the corrected pose continues from where the robot was.
    T_corrected_raw_ = entries_.back().T_world_robot * raw.Inverse();
    result = AddResult::kJumpCorrected;
  }
  last_raw_ = raw;
  OdometryEntry entry;
  entry.stamp_ns = sample.stamp_ns;
  entry.T_world_robot = T_corrected_raw_ * raw;
  entry.path_m = entries_.empty() ? 0.0
                                  : entries_.back().path_m + Distance(entries_.back().T_world_robot,
                                                                      entry.T_world_robot);
  entries_.push_back(entry);
  return result;
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
