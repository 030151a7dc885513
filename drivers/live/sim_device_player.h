// Emulated robot hardware for tests: a simulated run (drivers/sim/sim_stream.h)
// played in (scaled) real time through pseudo-terminals that speak the LT102
// protocol (one per radar; streaming starts when the configured start command
// arrives) and the Kobuki protocol (encoder ticks recovered exactly from the
// simulated tick odometry, 16-bit wrap-around included). Faults are injected on
// the wire: unplugging a radar, corrupted frames (garbage, truncation, bad
// escapes; Kobuki: bad checksums), an odometry stall and an encoder jump. The
// ground truth is kept, stamped by the same host clock the drivers use, so the
// live result can be scored.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "drivers/live/pty_device.h"
#include "drivers/sim/sim_stream.h"
#include "slam/config.h"

namespace uwbsar::live {

struct EmulatorFaults {
  int unplug_radar = 0;       ///< which radar is unplugged
  double unplug_at_s = -1.0;  ///< run time of the unplug (< 0: never)
  double unplug_for_s = 0.0;
  double corrupt_fraction = 0.0;  ///< fraction of LT102 frames and Kobuki packets corrupted
  double stall_at_s = -1.0;       ///< odometry silent from here (< 0: never)
  double stall_for_s = 0.0;
  double encoder_jump_at_s = -1.0;  ///< one packet with encoders jumped by 20000 ticks
  std::uint64_t seed = 7;
};

struct EmulatorCounts {
  long long scans_sent = 0;
  long long packets_sent = 0;
  long long frames_corrupted = 0;
  long long packets_corrupted = 0;
  long long bytes_dropped = 0;  ///< the host did not read fast enough (or was unplugged)
};

class SimDevicePlayer {
 public:
  /// `radar_links[i]` / `kobuki_link`: symlink paths the drivers open. `speed` = 1 plays at
  /// real time. `clock` stamps the ground truth (the drivers' clock). `max_duration_s` > 0
  /// stops early (shortened runs).
  SimDevicePlayer(const Config& config, const sim::SimScenario& scenario, std::uint64_t seed,
                  std::vector<std::string> radar_links, std::string kobuki_link, double speed,
                  int lt102_format, const EmulatorFaults& faults,
                  std::function<std::int64_t()> clock, double max_duration_s = 0.0);
  ~SimDevicePlayer();

  void Start();
  void Stop();
  bool done() const { return done_; }
  void WaitDone();
  /// Ground truth so far, stamped on the drivers' clock.
  std::vector<OdometrySample> ground_truth() const;
  EmulatorCounts counts() const;
  double duration_s() const { return duration_s_; }

 private:
  void Loop();
  void ServeCommands(int radar);
  void SendScan(int radar, const RadarScan& scan);
  void SendOdometry(TimestampNs sim_stamp_ns, const OdometrySample& odometry);

  Config config_;
  sim::SimStream stream_;
  double speed_;
  int format_;
  EmulatorFaults faults_;
  std::function<std::int64_t()> clock_;
  double duration_s_;
  std::vector<std::unique_ptr<PtyDevice>> radars_;
  std::vector<bool> streaming_;
  std::unique_ptr<PtyDevice> kobuki_;
  std::thread thread_;
  std::atomic<bool> stop_{false}, done_{false};
  mutable std::mutex mutex_;
  std::vector<OdometrySample> ground_truth_;
  EmulatorCounts counts_;
  // Kobuki state: ticks recovered from the simulated odometry.
  bool have_last_odometry_ = false;
  Pose2 last_odometry_;
  std::int64_t ticks_[2] = {0, 0};
  std::int64_t jump_ticks_ = 0;
  std::uint64_t rng_state_;
};

}  // namespace uwbsar::live
