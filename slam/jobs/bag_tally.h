// What `uwbsar map` would receive from a bag, counted topic by topic as the bag streams past
// (drivers/rosbag/robot_bag.h): per radar its scans, their rate and lengths; of the odometry
// its rate, header stamps going back, steps over gating.max_odom_jump_m and the scans it does
// not cover. Counters only, never the scans: `uwbsar check` (slam/jobs/check_job.h) judges them.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/pose2.h"
#include "drivers/rosbag/robot_bag.h"
#include "slam/app_config.h"

namespace uwbsar::slam {

/// Messages per second between the first and the last of `count` (0 when there are fewer
/// than two or no time between them).
inline double Rate(std::uint64_t count, TimestampNs first, TimestampNs last) {
  return count > 1 && last > first ? static_cast<double>(count - 1) / NsToSeconds(last - first)
                                   : 0.0;
}

struct RadarTally {
  std::uint64_t scans = 0;
  std::uint64_t wrong_length = 0;  ///< scans whose length is not radars[i].num_samples
  std::uint64_t zero = 0;          ///< scans of the right length, every sample zero
  std::size_t first_wrong_length = 0;
  TimestampNs first_wrong_ns = 0, first_ns = 0, last_ns = 0;
  double rate_hz() const { return Rate(scans, first_ns, last_ns); }
};

struct OdometryTally {
  std::uint64_t count = 0, header_stamped = 0;
  TimestampNs first_ns = 0, last_ns = 0;
  // Header stamps going back: how often, by how much at most, where first.
  std::uint64_t back = 0, first_back_message = 0;
  TimestampNs last_header_ns = 0, largest_back_ns = 0, first_back_ns = 0;
  // Steps between consecutive poses: how many over gating.max_odom_jump_m, the largest.
  std::uint64_t jumps = 0, largest_step_message = 0;
  double largest_step_m = 0.0;
  TimestampNs largest_step_ns = 0;
  std::optional<Pose2> last_pose;
  // Scans the odometry does not cover (as OdometryBuffer::Lookup): before its first message,
  // after its last (scans_since_last at the end), inside a gap over gating.max_odom_gap_s.
  // A scan stamped as an odometry message is covered by it, whatever the gap.
  std::uint64_t scans_since_last = 0, scans_before = 0, scans_in_gaps = 0, gaps = 0;
  std::uint64_t scans_at_latest = 0;  ///< of scans_since_last, those stamped latest_scan_ns
  TimestampNs latest_scan_ns = 0;
  TimestampNs largest_gap_ns = 0, largest_gap_at_ns = 0;
  double rate_hz() const { return Rate(count, first_ns, last_ns); }
};

/// Counts what `map` would receive, in the bag's receive-time order (ReadRobotBag).
class BagTally : public rosbag::RobotBagVisitor {
 public:
  /// `radar_of_sensor`: the reader's sensor id (index of RobotBagOptions::radar_topics) ->
  /// index of config.radars.
  BagTally(const Config& config, std::vector<int> radar_of_sensor)
      : config_(config),
        radar_of_sensor_(std::move(radar_of_sensor)),
        radars_(config.radars.size()) {}

  void OnRadarScan(const RadarScan& scan) override;
  void OnOdometryMessage(const rosbag::MessageContext& ctx, const rosbag::Odometry& msg) override;
  void OnOdometry(const OdometrySample& sample) override;
  void OnGroundTruth(const OdometrySample&) override { ++ground_truth_; }

  /// One per config.radars entry.
  const std::vector<RadarTally>& radars() const { return radars_; }
  const OdometryTally& odometry() const { return odometry_; }
  std::uint64_t ground_truth() const { return ground_truth_; }

 private:
  const Config& config_;
  std::vector<int> radar_of_sensor_;
  std::vector<RadarTally> radars_;
  OdometryTally odometry_;
  std::uint64_t ground_truth_ = 0;
};

}  // namespace uwbsar::slam
