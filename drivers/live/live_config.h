// Configuration of live mode on the robot (`uwbsar run`).
// Part of the configuration (slam/app_config.h aggregates it); fields are read and
// written by the generic loader in core/config_io.h.
#pragma once

#include <string>
#include <vector>

namespace uwbsar {

/// The LT102 settings sent at start-up (the vendor toolbox's command protocol,
/// drivers/live/lt102_commands.h holds the command table).
/// The radar's echoed range, not radars[].range_offset_m / num_samples, sets the range of
/// sample 0 and the sample count that imaging uses in a live run.
struct Lt102Config {
  std::string crc = "auto";       ///< trailing CRC-8 byte: auto (from the version answer), off, on
  int channel = 0;                ///< `$` data channel: 0-3 one receive channel, 4 combined
  int sample_format = 1;          ///< 0x0A: 0 Q7, 1 Q15, 2 Q31, 3 F32, 4 F16
  double range_min_m = 0.0;       ///< `x`: range of the first sample asked for
  double range_max_m = 6.42;      ///< `X`: range of the last sample asked for
  int frame_rate_fps = 100;       ///< `f`: acquisition rate asked; the answer (the actual
                                  ///< rate) paces the `d` polls
  int crc_polynomial = 0x07;      ///< CRC-8 polynomial (not public; default CRC-8/SMBUS)
  int crc_init = 0x00;            ///< CRC-8 initial value
  double answer_timeout_s = 0.5;  ///< start-up and stop: wait for an answer this long
  double frame_timeout_s = 0.1;   ///< acquisition: a `d` unanswered this long is lost
  double startup_wait_s = 10.0;   ///< `uwbsar run` waits this long for every radar's start-up
                                  ///< (its echoed range) before SLAM starts

  template <class V>
  void Visit(V& v) {
    v("channel", channel);
    v("sample_format", sample_format);
    v("range_min_m", range_min_m);
    v("range_max_m", range_max_m);
    v("frame_rate_fps", frame_rate_fps);
    v("crc", crc);
    v("crc_polynomial", crc_polynomial);
    v("crc_init", crc_init);
    v("answer_timeout_s", answer_timeout_s);
    v("frame_timeout_s", frame_timeout_s);
    v("startup_wait_s", startup_wait_s);
  }
};

/// Live mode on the robot (`uwbsar run`): serial devices, GPIO wiring, threads and
/// recording. Device paths and GPIO lines are the robot's; config/robot.yaml is the
/// paper's robot.
struct LiveConfig {
  /// The radars' model: which driver runs each of them (drivers/live/radar_driver_factory.h
  /// lists the registered models; "lt102": the LT102 over serial, live.lt102.*)
  std::string radar_model = "lt102";
  std::vector<std::string> radar_devices = {
      "/dev/ttyACM0", "/dev/ttyACM1"};           ///< serial
                                                 ///< device of radars[i] (one per radar)
  int radar_baud = 115200;                       ///< LT102 baud rate (SDK default)
  std::string kobuki_device = "/dev/kobuki";     ///< Kobuki base serial device
  int kobuki_baud = 115200;                      ///< Kobuki baud rate
  double kobuki_wheel_radius_m = 0.035;          ///< Kobuki wheel radius
  double kobuki_wheelbase_m = 0.230;             ///< Kobuki wheel separation
  double kobuki_ticks_per_revolution = 2578.33;  ///< Kobuki encoder ticks per wheel turn
  double max_wheel_speed_mps = 1.0;    ///< a wheel faster than this between two packets is
                                       ///< an odometry jump: the step is not integrated
  double odometry_stall_s = 0.5;       ///< no odometry for this long: reported as a stall
  std::string gpio_chip = "";          ///< libgpiod chip (e.g. gpiochip0); "" = no GPIO
  std::vector<int> radar_power_lines;  ///< power-enable line of radars[i]; [] = not wired
  std::vector<int> radar_reset_lines;  ///< reset line (active low) of radars[i]; [] = not wired
  int status_led_line = -1;            ///< status LED line; -1 = not wired
  double reset_pulse_s = 0.1;          ///< reset held low this long
  double power_settle_s = 0.5;         ///< wait after power-on and after reset
  double power_off_s = 1.0;            ///< power held off this long in a power cycle
  int power_cycle_after_failures = 3;  ///< reconnect failures before a radar is power cycled
  double read_timeout_s = 1.0;         ///< a link silent this long is reconnected
  double reconnect_initial_s = 0.2;    ///< first reconnect delay, doubled per failure
  double reconnect_max_s = 5.0;        ///< reconnect delay cap
  /// SCHED_FIFO priority (1-99) of the device link threads (and the emulator's), so a busy
  /// CPU does not make them poll late; 0 = normal priority. Refused without the right to
  /// (root, CAP_SYS_NICE or an rtprio limit): one warning, the run goes on.
  int driver_priority = 20;
  int processing_queue_size = 4000;  ///< messages waiting for SLAM; beyond, the oldest
                                     ///< are dropped from processing (never from recording)
  /// Serial: stamped messages of the radars and the base are put back in stamp order
  /// within this much wall time before SLAM and the recording see them.
  double reorder_window_s = 0.1;
  double snapshot_period_s = 10.0;  ///< map outputs are rewritten this often (0 = only at end)
  std::string recording_storage = "sqlite3";  ///< recording bag storage: sqlite3 or mcap (both
                                              ///< survive a crash up to the last flush)
  double recording_flush_period_s = 0.5;      ///< the recording is made durable this often
  double clock_step_threshold_s = 0.1;        ///< host clock moving this much against the
                                              ///< monotonic clock is reported as a clock step
  Lt102Config lt102;                          ///< LT102 start-up settings and link timing

  template <class V>
  void Visit(V& v) {
    v("radar_model", radar_model);
    v("radar_devices", radar_devices);
    v("radar_baud", radar_baud);
    v("kobuki_device", kobuki_device);
    v("kobuki_baud", kobuki_baud);
    v("kobuki_wheel_radius_m", kobuki_wheel_radius_m);
    v("kobuki_wheelbase_m", kobuki_wheelbase_m);
    v("kobuki_ticks_per_revolution", kobuki_ticks_per_revolution);
    v("max_wheel_speed_mps", max_wheel_speed_mps);
    v("odometry_stall_s", odometry_stall_s);
    v("gpio_chip", gpio_chip);
    v("radar_power_lines", radar_power_lines);
    v("radar_reset_lines", radar_reset_lines);
    v("status_led_line", status_led_line);
    v("reset_pulse_s", reset_pulse_s);
    v("power_settle_s", power_settle_s);
    v("power_off_s", power_off_s);
    v("power_cycle_after_failures", power_cycle_after_failures);
    v("read_timeout_s", read_timeout_s);
    v("reconnect_initial_s", reconnect_initial_s);
    v("reconnect_max_s", reconnect_max_s);
    v("driver_priority", driver_priority);
    v("processing_queue_size", processing_queue_size);
    v("reorder_window_s", reorder_window_s);
    v("snapshot_period_s", snapshot_period_s);
    v("recording_storage", recording_storage);
    v("recording_flush_period_s", recording_flush_period_s);
    v("clock_step_threshold_s", clock_step_threshold_s);
    v("lt102", lt102);
  }
};

/// Semantic checks of live.* (ranges, names, consistency); throws ConfigError naming the
/// dotted key and `source_name`.
void Validate(const LiveConfig& config, const std::string& source_name);

}  // namespace uwbsar
