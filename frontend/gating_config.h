// Settings of gating.*, declared beside the code that owns them (frontend/odometry_buffer.h and the
// scan gate); the application configuration (slam/config/system_config.h, slam/app_config.h)
// assembles the sections, and core/config_io.h reads and writes any struct with a Visit().
// config/default.yaml documents every field; a test keeps the two in sync.
#pragma once

#include <string>

namespace uwbsar {

/// Scan gating and odometry sanity checks.
struct GatingConfig {
  double min_travel_m = 0.003;   ///< accept a scan after this much robot travel (paper: 3 mm)
  double max_odom_jump_m = 0.5;  ///< a larger step between consecutive odometry samples is rejected
  double max_odom_gap_s = 0.5;   ///< scans farther than this from odometry samples are rejected
  double max_scan_latency_s = 1.0;   ///< scans waiting longer than this for odometry are dropped
  double max_odom_speed_mps = 10.0;  ///< a step implying a faster speed is an outlier or a reset
  double max_odom_turn_rate_radps = 12.0;  ///< a step implying a faster turn likewise

  template <class V>
  void Visit(V& v) {
    v("min_travel_m", min_travel_m);
    v("max_odom_jump_m", max_odom_jump_m);
    v("max_odom_gap_s", max_odom_gap_s);
    v("max_scan_latency_s", max_scan_latency_s);
    v("max_odom_speed_mps", max_odom_speed_mps);
    v("max_odom_turn_rate_radps", max_odom_turn_rate_radps);
  }
};
/// Semantic checks of gating.*; throws ConfigError naming the dotted key.
void Validate(const GatingConfig& config, const std::string& source_name);

}  // namespace uwbsar
