// Emulated robot hardware for tests: a simulated run (drivers/sim/sim_stream.h)
// played in (scaled) real time through pseudo-terminals that speak the LT102 command
// protocol (one lt102_emulator.h per radar: each simulated scan is a frame acquired,
// handed out when the driver polls `d`) and the Kobuki protocol (encoder ticks
// recovered exactly from the simulated tick odometry, 16-bit wrap-around included).
// Faults are injected on the wire: unplugging a radar, corrupted frames (garbage,
// truncation, bad escapes; Kobuki: bad checksums), an odometry stall, an encoder jump,
// and the LT102 faults of lt102_emulator.h (wrong echo, missing answer, bad frame size,
// frames with a CRC byte). The radars keep answering commands after the run ends, until
// Stop(), so the drivers' stop is acknowledged. The
// ground truth is kept, stamped by the same host clock the drivers use, so the
// live result can be scored.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "drivers/emulators/emulator_settings.h"
#include "drivers/emulators/lt102_emulator.h"
#include "drivers/emulators/pty_device.h"
#include "drivers/sim/sim_stream.h"

namespace uwbsar::live {

struct EmulatorFaults {
  int unplug_radar = 0;       ///< which radar is unplugged
  double unplug_at_s = -1.0;  ///< run time of the unplug (< 0: never)
  double unplug_for_s = 0.0;
  double corrupt_fraction = 0.0;  ///< fraction of LT102 frames and Kobuki packets corrupted
  double stall_at_s = -1.0;       ///< odometry silent from here (< 0: never)
  double stall_for_s = 0.0;
  double encoder_jump_at_s = -1.0;  ///< one packet with encoders jumped by 20000 ticks
  // LT102 faults, on every radar (see Lt102EmulatorOptions).
  int lt102_wrong_echo_code = -1;      ///< this command's echo is off by one
  int lt102_missing_answer_code = -1;  ///< this command goes unanswered ...
  int lt102_missing_answer_times = 1;  ///< ... this many times
  int lt102_bad_size_every = 0;        ///< every n-th `d` answer is two bytes short
  bool lt102_crc = false;              ///< the radars append a CRC-8 byte to every answer
  int lt102_carrier_mhz = 0;           ///< the radars' carrier; 0 = pulse.center_frequency_hz
  /// The radars' `f` answer (they acquire at the simulated scan rate whatever is asked);
  /// 0 = the rate asked.
  int lt102_actual_frame_rate_fps = 0;
  /// `d` polled before the next frame waits for it instead of repeating the latest one
  /// (Lt102EmulatorOptions::hold_d_until_next_frame; the vendor behaviour repeats).
  bool lt102_hold_d_until_next_frame = false;
  std::uint64_t seed = 7;
};

struct EmulatorCounts {
  long long scans_sent = 0;          ///< LT102 frames answered to `d` requests
  long long frames_acquired = 0;     ///< simulated scans while the radars were started
  long long frames_overwritten = 0;  ///< acquired but replaced before a `d` asked for them
  long long frames_repeated = 0;     ///< `d` answered with a frame already handed out
  long long frames_missed = 0;       ///< overwritten after the acquisition's first answer
  long long packets_sent = 0;
  long long frames_corrupted = 0;
  long long packets_corrupted = 0;
  long long bytes_dropped = 0;  ///< the host did not read fast enough (or was unplugged)
};

class SimDevicePlayer {
 public:
  /// `radar_links[i]` / `kobuki_link`: symlink paths the drivers open. `speed` = 1 plays at
  /// real time. `clock` stamps the ground truth (the drivers' clock). `max_duration_s` > 0
  /// stops early (shortened runs). The drivers must poll at the emulated frame rate:
  /// see ConfigureLiveForEmulation.
  SimDevicePlayer(const EmulatorSettings& config, const sim::SimScenario& scenario,
                  std::uint64_t seed, std::vector<std::string> radar_links, std::string kobuki_link,
                  double speed, const EmulatorFaults& faults, std::function<std::int64_t()> clock,
                  double max_duration_s = 0.0);
  ~SimDevicePlayer();

  void Start();
  void Stop();
  /// The simulated run has been played (the radars still answer commands).
  bool done() const { return done_; }
  /// Ground truth so far, stamped on the drivers' clock.
  std::vector<OdometrySample> ground_truth() const;
  /// Each radar's frames' true times on the host clock (the simulated run's acquisition
  /// times, played from the start of the run), whenever this thread got to them.
  std::vector<std::vector<TimestampNs>> scan_send_ns() const;
  EmulatorCounts counts() const;
  double duration_s() const { return duration_s_; }

 private:
  void Loop();
  void SendScan(int radar, const RadarScan& scan, std::chrono::steady_clock::time_point due);
  void SendOdometry(TimestampNs sim_stamp_ns, const OdometrySample& odometry);

  EmulatorSettings config_;
  sim::SimStream stream_;
  double speed_;
  EmulatorFaults faults_;
  std::function<std::int64_t()> clock_;
  double duration_s_;
  std::vector<std::unique_ptr<Lt102Emulator>> radars_;
  std::unique_ptr<PtyDevice> kobuki_;
  std::thread thread_;
  std::atomic<bool> stop_{false}, done_{false};
  mutable std::mutex mutex_;
  std::vector<OdometrySample> ground_truth_;
  std::vector<std::vector<TimestampNs>> scan_send_ns_;
  EmulatorCounts counts_;
  // Kobuki state: ticks recovered from the simulated odometry.
  bool have_last_odometry_ = false;
  Pose2 last_odometry_;
  std::int64_t ticks_[2] = {0, 0};
  std::int64_t jump_ticks_ = 0;
  std::uint64_t rng_state_;
};

/// The live settings that must match the emulated devices at playback `speed`: the LT102
/// frame rate (the simulated scan rate, scaled) that the drivers poll at.
void ConfigureLiveForEmulation(const SimulatorConfig& simulator, double speed, LiveConfig* live);

}  // namespace uwbsar::live
