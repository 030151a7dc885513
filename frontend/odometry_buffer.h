// Recent wheel-odometry samples, interpolated at scan timestamps. Odometry that
// jumps (a step longer than gating.max_odom_jump_m between consecutive samples,
// e.g. a driver reset) is re-anchored so the trajectory stays continuous: the
// jump is treated as zero motion and counted, never imaged as a teleport.
#pragma once

#include <deque>
#include <optional>

#include "slam/config.h"
#include "slam/types.h"

namespace uwbsar {

struct OdometryEntry {
  TimestampNs stamp_ns = 0;
  Pose2 T_world_robot;  ///< after jump correction
  double path_m = 0.0;  ///< distance travelled since the first sample
};

class OdometryBuffer {
 public:
  enum class AddResult { kAccepted, kJumpCorrected, kOutOfOrder, kNonFinite };
  enum class LookupResult { kOk, kBeforeFirst, kAfterLast, kGap };

  explicit OdometryBuffer(const GatingConfig& config) : config_(config) {}

  AddResult Add(const OdometrySample& sample);
  /// Pose and path length at `stamp_ns` by interpolation between the bracketing samples.
  LookupResult Lookup(TimestampNs stamp_ns, OdometryEntry* out) const;
  /// Drops samples older than `stamp_ns`, keeping one before it for interpolation.
  void TrimBefore(TimestampNs stamp_ns);

  bool empty() const { return entries_.empty(); }
  TimestampNs latest_stamp_ns() const { return entries_.empty() ? 0 : entries_.back().stamp_ns; }
  const std::deque<OdometryEntry>& entries() const { return entries_; }

 private:
  GatingConfig config_;
  std::deque<OdometryEntry> entries_;
  std::optional<Pose2> last_raw_;
  Pose2 T_corrected_raw_;  ///< applied to raw poses after a jump
};

}  // namespace uwbsar
