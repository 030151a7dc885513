#include "drivers/live/live_config.h"

#include <cmath>
#include <string>

#include "core/config_require.h"
#include "drivers/live/radar_driver_factory.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const LiveConfig& l, const std::string& src) {
  const std::string k = "live.";
  if (!live::IsRadarModel(l.radar_model)) {
    std::string known;
    for (const std::string& m : live::RadarModels()) known += (known.empty() ? "" : ", ") + m;
    Require(false, src, k + "radar_model",
            "is '" + l.radar_model + "', not a known radar model (" + known + ")");
  }
  for (std::size_t i = 0; i < l.radar_devices.size(); ++i) {
    Require(!l.radar_devices[i].empty(), src, k + "radar_devices[" + std::to_string(i) + "]",
            "must not be empty");
  }
  Require(l.radar_baud > 0, src, k + "radar_baud", "must be > 0");
  Require(l.kobuki_baud > 0, src, k + "kobuki_baud", "must be > 0");
  const Lt102Config& t = l.lt102;
  const std::string kt = k + "lt102.";
  Require(t.channel >= 0 && t.channel <= 4, src, kt + "channel",
          "must be in [0, 4] (0-3 one channel, 4 combined; 5 = all is not supported)");
  Require(t.sample_format >= 0 && t.sample_format <= 4, src, kt + "sample_format",
          "must be in [0, 4] (0 Q7, 1 Q15, 2 Q31, 3 F32, 4 F16)");
  Require(std::isfinite(t.range_min_m) && t.range_min_m >= 0, src, kt + "range_min_m",
          "must be >= 0");
  Require(std::isfinite(t.range_max_m) && t.range_max_m > t.range_min_m, src, kt + "range_max_m",
          "must be > live.lt102.range_min_m");
  Require(t.frame_rate_fps >= 1 && t.frame_rate_fps <= 32767, src, kt + "frame_rate_fps",
          "must be in [1, 32767]");
  Require(t.crc == "auto" || t.crc == "off" || t.crc == "on", src, kt + "crc",
          "must be auto, off or on");
  Require(t.crc_polynomial >= 0 && t.crc_polynomial <= 255, src, kt + "crc_polynomial",
          "must be in [0, 255]");
  Require(t.crc_init >= 0 && t.crc_init <= 255, src, kt + "crc_init", "must be in [0, 255]");
  Require(t.answer_timeout_s > 0, src, kt + "answer_timeout_s", "must be > 0");
  Require(t.frame_timeout_s > 0, src, kt + "frame_timeout_s", "must be > 0");
  Require(t.startup_wait_s >= 0, src, kt + "startup_wait_s", "must be >= 0");
  Require(!l.kobuki_device.empty(), src, k + "kobuki_device", "must not be empty");
  Require(l.kobuki_wheel_radius_m > 0, src, k + "kobuki_wheel_radius_m", "must be > 0");
  Require(l.kobuki_wheelbase_m > 0, src, k + "kobuki_wheelbase_m", "must be > 0");
  Require(l.kobuki_ticks_per_revolution > 0, src, k + "kobuki_ticks_per_revolution", "must be > 0");
  Require(l.max_wheel_speed_mps > 0, src, k + "max_wheel_speed_mps", "must be > 0");
  Require(l.odometry_stall_s > 0, src, k + "odometry_stall_s", "must be > 0");
  const std::size_t n = l.radar_devices.size();
  Require(l.radar_power_lines.empty() || l.radar_power_lines.size() == n, src,
          k + "radar_power_lines", "must be empty or list one line per radar_devices entry");
  Require(l.radar_reset_lines.empty() || l.radar_reset_lines.size() == n, src,
          k + "radar_reset_lines", "must be empty or list one line per radar_devices entry");
  for (int line : l.radar_power_lines) {
    Require(line >= 0, src, k + "radar_power_lines", "line offsets must be >= 0");
  }
  for (int line : l.radar_reset_lines) {
    Require(line >= 0, src, k + "radar_reset_lines", "line offsets must be >= 0");
  }
  Require(l.status_led_line >= -1, src, k + "status_led_line", "must be >= 0, or -1 (none)");
  const bool wired =
      !l.radar_power_lines.empty() || !l.radar_reset_lines.empty() || l.status_led_line >= 0;
  Require(!wired || !l.gpio_chip.empty(), src, k + "gpio_chip",
          "must name a chip when GPIO lines are configured");
  Require(l.reset_pulse_s > 0, src, k + "reset_pulse_s", "must be > 0");
  Require(l.power_settle_s >= 0, src, k + "power_settle_s", "must be >= 0");
  Require(l.power_off_s > 0, src, k + "power_off_s", "must be > 0");
  Require(l.power_cycle_after_failures >= 1, src, k + "power_cycle_after_failures", "must be >= 1");
  Require(l.read_timeout_s > 0, src, k + "read_timeout_s", "must be > 0");
  Require(l.reconnect_initial_s > 0, src, k + "reconnect_initial_s", "must be > 0");
  Require(l.reconnect_max_s >= l.reconnect_initial_s, src, k + "reconnect_max_s",
          "must be >= reconnect_initial_s");
  Require(l.driver_priority >= 0 && l.driver_priority <= 99, src, k + "driver_priority",
          "must be 0 (normal priority) or a SCHED_FIFO priority 1..99");
  Require(l.processing_queue_size >= 1, src, k + "processing_queue_size", "must be >= 1");
  Require(l.snapshot_period_s >= 0, src, k + "snapshot_period_s", "must be >= 0");
  Require(l.recording_storage == "mcap" || l.recording_storage == "sqlite3", src,
          k + "recording_storage", "must be 'mcap' or 'sqlite3'");
  Require(l.recording_flush_period_s > 0 && l.recording_flush_period_s <= 1, src,
          k + "recording_flush_period_s", "must be in (0, 1]");
  Require(l.clock_step_threshold_s > 0, src, k + "clock_step_threshold_s", "must be > 0");
}

}  // namespace uwbsar
