// `uwbsar run --emulate`: the robot's devices replaced by emulated ones on pseudo-terminals in
// <out>/dev (an LT102 per configured radar and the Kobuki base) that play a simulated
// depart-and-return run (drivers/emulators/sim_device_player.h); the live configuration is
// pointed at them and the run ends when the playback does.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "slam/app_config.h"
#include "slam/live/live_runner.h"

namespace uwbsar::live {
class HostClock;
class SimDevicePlayer;
}  // namespace uwbsar::live

namespace uwbsar::slam {

struct EmulationOptions {
  std::string map_yaml;     ///< the map_server map the run is simulated in
  std::uint64_t seed = 1;   ///< simulation seed
  double speed = 1.0;       ///< playback speed (1 = real time)
  double duration_s = 0.0;  ///< > 0: play only this many seconds
};

/// The emulated devices of a live run and the thread that stops the run when they end.
class LiveEmulation {
 public:
  /// Creates <options->out_dir>/dev, points config->live at emulated devices there (no GPIO,
  /// the LT102 frame rate of the simulation at `emulation.speed`), sets options->time_scale and
  /// options->ground_truth (the played run's, stamped on a clock started with the run's),
  /// starts the devices, and a watcher that sets `*stop` 50 ms after the playback ends (or
  /// returns when `*stop` is set first). The caller locks options->out_dir before
  /// (LockLiveOutputFolder). Throws InputError on a bad map (nothing is started then).
  LiveEmulation(const EmulationOptions& emulation, Config* config, LiveRunOptions* options,
                std::atomic<bool>* stop);
  /// As Finish(), after setting `*stop` if the watcher still runs (the run failed).
  ~LiveEmulation();
  LiveEmulation(const LiveEmulation&) = delete;
  LiveEmulation& operator=(const LiveEmulation&) = delete;

  /// After the run: waits for the watcher (until the playback ends or `*stop` is set), then
  /// stops the devices and removes <out>/dev when this made it and it is empty.
  void Finish();

 private:
  std::atomic<bool>* stop_;
  std::string dev_dir_;           ///< <out>/dev, the devices' folder
  bool created_dev_dir_ = false;  ///< made here: removed once the devices are stopped
  // Destroyed in reverse order: the watcher (reads the player), the player (reads the
  // clock), the clock.
  std::unique_ptr<live::HostClock> truth_clock_;
  std::unique_ptr<live::SimDevicePlayer> player_;
  std::thread watcher_;
};

}  // namespace uwbsar::slam
