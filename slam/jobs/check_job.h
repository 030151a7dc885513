// The job behind `uwbsar check BAG`: a recording read as `uwbsar map` reads it (the topics of
// the configuration, drivers/rosbag/robot_bag.h), streamed once, and judged against the
// configuration before any mapping: one line per check, each ok, info, warning or error.
// An error is what would make `map` fail, or lose data with at most a log line: a configured
// topic missing, of the wrong type or without messages, scans whose length is not
// radars[].num_samples or that are all zero, scans outside the odometry (gaps over
// gating.max_odom_gap_s), odometry header stamps going back (the receive order, which map
// follows, is not the order the base stamped). A warning is what map copes with but the user
// should know: odometry much slower than the scans (each scan's pose interpolated over a longer
// stretch; the demo's run with odometry at 10 Hz instead of 50 Hz still mapped to 0.71 cm ATE,
// so not an error), odometry jumps over gating.max_odom_jump_m (map takes each as no motion).
// Memory: counters per topic (slam/jobs/bag_tally.h), never the scans.
#pragma once

#include <string>
#include <vector>

#include "slam/app_config.h"

namespace uwbsar::slam {

enum class CheckLevel { kOk, kInfo, kWarning, kError };

struct CheckLine {
  CheckLevel level = CheckLevel::kOk;
  std::string text;  ///< what was found, naming the topic and the configuration key
};

struct BagCheck {
  std::vector<CheckLine> lines;  ///< in a fixed order: bag, each radar, odometry, ground truth
  int Count(CheckLevel level) const;
};

/// More scans of one radar per odometry interval than this is a warning (the paper's robot
/// and the simulator record 2: radars at 100 Hz, the base at 50 Hz).
inline constexpr double kMaxScansPerOdometry = 4.0;
/// Of a radar's scans, a larger share of the wrong length is an error, a smaller one a warning;
/// of all scans, a larger share outside the odometry is an error, a smaller one (a few before
/// the base's first message or after its last) is ok.
inline constexpr double kMaxLostScanShare = 0.01;

/// Reads `bag` (directory, .db3 or .mcap) once and checks it against `config`. Throws
/// InputError, as `map` does, when the bag cannot be opened or a message cannot be decoded.
BagCheck CheckBag(const Config& config, const std::string& bag);

/// "ok      ", "info    ", "warning ", "error   " followed by the line's text.
std::string FormatCheckLine(const CheckLine& line);

}  // namespace uwbsar::slam
