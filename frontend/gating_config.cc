#include "frontend/gating_config.h"

#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const GatingConfig& g, const std::string& src) {
  Require(g.min_travel_m >= 0, src, "gating.min_travel_m", "must be >= 0");
  Require(g.max_odom_jump_m > 0, src, "gating.max_odom_jump_m", "must be > 0");
  Require(g.max_odom_gap_s > 0, src, "gating.max_odom_gap_s", "must be > 0");
  Require(g.max_scan_latency_s > 0, src, "gating.max_scan_latency_s", "must be > 0");
  Require(g.max_odom_speed_mps > 0, src, "gating.max_odom_speed_mps", "must be > 0");
  Require(g.max_odom_turn_rate_radps > 0, src, "gating.max_odom_turn_rate_radps", "must be > 0");
}

}  // namespace uwbsar
