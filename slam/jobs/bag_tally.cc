#include "slam/jobs/bag_tally.h"

#include <algorithm>

namespace uwbsar::slam {

void BagTally::OnRadarScan(const RadarScan& scan) {
  const int i = radar_of_sensor_[static_cast<std::size_t>(scan.sensor_id)];
  RadarTally& r = radars_[static_cast<std::size_t>(i)];
  if (r.scans++ == 0) r.first_ns = scan.stamp_ns;
  r.last_ns = scan.stamp_ns;
  OdometryTally& o = odometry_;
  if (o.count == 0 || scan.stamp_ns > o.last_ns) {
    o.scans_at_latest =
        o.scans_since_last++ > 0 && scan.stamp_ns == o.latest_scan_ns ? o.scans_at_latest + 1 : 1;
    o.latest_scan_ns = scan.stamp_ns;
  }
  if (static_cast<int>(scan.samples.size()) != config_.radars[i].num_samples) {
    if (r.wrong_length++ == 0) {
      r.first_wrong_length = scan.samples.size();
      r.first_wrong_ns = scan.stamp_ns;
    }
  } else if (std::all_of(scan.samples.begin(), scan.samples.end(),
                         [](float v) { return v == 0.0f; })) {
    ++r.zero;
  }
}

void BagTally::OnOdometryMessage(const rosbag::MessageContext& ctx, const rosbag::Odometry& msg) {
  if (ctx.topic != config_.slam.odometry_topic) return;
  const TimestampNs header_ns =
      static_cast<TimestampNs>(msg.header.stamp.sec) * 1000000000 + msg.header.stamp.nanosec;
  if (header_ns == 0) return;  // not stamped: map uses the receive time anyway
  OdometryTally& o = odometry_;
  if (o.header_stamped++ > 0 && header_ns < o.last_header_ns) {
    if (o.back++ == 0) {
      o.first_back_message = o.count;
      o.first_back_ns = ctx.log_time_ns;
    }
    o.largest_back_ns = std::max(o.largest_back_ns, o.last_header_ns - header_ns);
  }
  o.last_header_ns = header_ns;
}

void BagTally::OnOdometry(const OdometrySample& sample) {
  OdometryTally& o = odometry_;
  const std::uint64_t between =
      o.scans_since_last - (o.latest_scan_ns == sample.stamp_ns ? o.scans_at_latest : 0);
  if (o.count == 0) {
    o.first_ns = sample.stamp_ns;
    o.scans_before = between;
  } else {
    const TimestampNs gap = sample.stamp_ns - o.last_ns;
    if (NsToSeconds(gap) > config_.gating.max_odom_gap_s) {
      o.scans_in_gaps += between;
      ++o.gaps;
    }
    if (gap > o.largest_gap_ns) {
      o.largest_gap_ns = gap;
      o.largest_gap_at_ns = o.last_ns;
    }
    const double step = Distance(*o.last_pose, sample.T_world_robot);
    o.jumps += step > config_.gating.max_odom_jump_m;
    if (step > o.largest_step_m) {
      o.largest_step_m = step;
      o.largest_step_ns = sample.stamp_ns;
      o.largest_step_message = o.count;
    }
  }
  o.scans_since_last = 0;
  o.last_pose = sample.T_world_robot;
  o.last_ns = sample.stamp_ns;
  ++o.count;
}

}  // namespace uwbsar::slam
