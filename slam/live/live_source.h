// Where `uwbsar run` gets its input (slam/live/live_runner.h): the robot's devices (radars
// of live.radar_model, drivers/live/radar_driver_factory.h; Kobuki base, GPIO) or a ROS 2
// robot over DDS. A source hands every
// message to the Dispatcher from its own threads; the run's main thread calls Poll()
// every 50 ms for watchdog work until the run is stopped.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "drivers/live/fault_log.h"
#include "drivers/live/radar_device.h"
#include "slam/app_config.h"
#include "slam/live/live_processor.h"

namespace uwbsar::slam {

class LiveSource {
 public:
  virtual ~LiveSource() = default;
  /// Starts delivering messages.
  virtual void Start() = 0;
  /// After Start, before SLAM is built: adapts `config` to what the devices reported
  /// (serial: each radar's start-up range sets radars[i].range_offset_m and num_samples).
  /// Throws InputError when a device refused its configuration.
  virtual void ConfigureImaging(Config* /*config*/) {}
  /// Watchdog work (stalls, clock steps, status LED); main thread, every 50 ms.
  virtual void Poll() = 0;
  /// Stops delivering: no message is dispatched after it returns.
  virtual void Stop() = 0;
  /// Stops what must outlive the drain of the SLAM queue (e.g. radar power); after Stop.
  virtual void ShutDown() {}
  virtual long long scans_received() const = 0;
  /// Per-radar counts by name ("radar left"; serial radars; after Stop).
  virtual std::vector<std::pair<std::string, live::RadarStats>> radar_stats() const { return {}; }
};

/// The robot's devices: GPIO power-up and reset (throws GpioError when a configured chip or
/// line is missing), one radar of live.radar_model per radars[] entry (created through
/// drivers/live/radar_driver_factory.h; ConfigError for an unknown model) and the Kobuki
/// driver over a reconnecting link. Messages are stamped on the host clock.
std::unique_ptr<LiveSource> MakeSerialSource(const Config& config, LiveRunOptions& options,
                                             Dispatcher* dispatcher, live::FaultLog* faults,
                                             live::HostClock* clock);

/// A ROS 2 robot over DDS (radar and odometry topics of the config); publishes the map,
/// pose, path and loops for RViz2 through `processor`'s hooks. Messages keep the
/// publisher's stamps (see dds.stamp).
std::unique_ptr<LiveSource> MakeRos2Source(const Config& config, Dispatcher* dispatcher,
                                           live::FaultLog* faults, Processor* processor);

}  // namespace uwbsar::slam
