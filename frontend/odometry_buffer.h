// Recent wheel-odometry samples, interpolated at scan timestamps. The one intake of
// odometry for every command (map, run, image, detectors go through ImagingFrontend).
//
// Sanity rules, in order, for each sample:
//  - a NaN/Inf pose, or a coordinate beyond kMaxOdomCoordinateM, is rejected;
//  - a stamp not after the newest sample's is rejected (out of order);
//  - a step from the last accepted sample that implies a speed above
//    gating.max_odom_speed_mps or a turn rate above gating.max_odom_turn_rate_radps is
//    impossible for the robot. The sample is held back and the next one decides: if the
//    next agrees with the last accepted sample, the held one was a single outlier and is
//    dropped (e.g. x = 1e20 from a corrupted message); if the next agrees with the held
//    one, the odometry really moved (a driver reset): the held sample is kept as a jump
//    (re-anchored, whatever its length);
//  - a step longer than gating.max_odom_jump_m (a driver reset) is re-anchored so the
//    trajectory stays continuous: the jump is treated as zero motion and counted, never
//    imaged as a teleport.
// Speeds are taken over at least kMinSpeedWindowS, so that stamps bunched by clock
// jitter do not turn an ordinary step into an impossible speed.
#pragma once

#include <deque>
#include <optional>

#include "core/types.h"
#include "frontend/gating_config.h"

namespace uwbsar {

/// Larger odometry coordinates are not on Earth (UTM northings stay below 1e7 m).
constexpr double kMaxOdomCoordinateM = 1e9;
/// Shortest time over which an implied speed or turn rate is measured.
constexpr double kMinSpeedWindowS = 0.02;

struct OdometryEntry {
  TimestampNs stamp_ns = 0;
  Pose2 T_world_robot;  ///< after jump correction
  double path_m = 0.0;  ///< distance travelled since the first sample
};

class OdometryBuffer {
 public:
  enum class AddResult {
    kAccepted,    ///< appended (see AddReport for a held sample appended before it)
    kHeld,        ///< implausible step: waits for the next sample to decide
    kOutOfOrder,  ///< dropped
    kNonFinite,   ///< dropped: NaN/Inf or a coordinate beyond kMaxOdomCoordinateM
  };
  enum class LookupResult { kOk, kBeforeFirst, kAfterLast, kGap };

  /// What one Add() did.
  struct AddReport {
    AddResult result = AddResult::kAccepted;
    int appended = 0;              ///< entries appended: this sample, and a held one before it
    int jumps = 0;                 ///< jumps re-anchored (0..2)
    bool outlier_dropped = false;  ///< an earlier held sample turned out to be an outlier
  };

  explicit OdometryBuffer(const GatingConfig& config) : config_(config) {}

  AddReport Add(const OdometrySample& sample);
  /// End of the stream: a sample still held back has nothing to confirm it and is
  /// dropped as an outlier; returns true if there was one.
  bool DropHeld();
  /// Pose and path length at `stamp_ns` by interpolation between the bracketing samples.
  LookupResult Lookup(TimestampNs stamp_ns, OdometryEntry* out) const;
  /// Drops samples older than `stamp_ns`, keeping one before it for interpolation.
  void TrimBefore(TimestampNs stamp_ns);

  bool empty() const { return entries_.empty(); }
  TimestampNs latest_stamp_ns() const { return entries_.empty() ? 0 : entries_.back().stamp_ns; }
  const std::deque<OdometryEntry>& entries() const { return entries_; }

 private:
  /// Whether moving from `a` to `b` is possible for the robot (speed and turn rate).
  bool Plausible(const OdometrySample& a, const OdometrySample& b) const;
  /// Appends a sample that passed the checks, re-anchored as a jump if `jump` or if its
  /// step is longer than max_odom_jump_m; returns true if it was a jump.
  bool Append(const OdometrySample& sample, bool jump);

  GatingConfig config_;
  std::deque<OdometryEntry> entries_;
  std::optional<OdometrySample> last_raw_;  ///< the last accepted sample, as received
  std::optional<OdometrySample> held_;      ///< an implausible sample awaiting the next
  Pose2 T_corrected_raw_;                   ///< applied to raw poses after a jump
};

}  // namespace uwbsar
