// A radar of a live run behind one seam, so that the live runtime (slam/live) knows no radar
// model: the factory (drivers/live/radar_driver_factory.h) creates one from live.radar_model.
// A device acquires on its own thread(s) between Start and Stop and hands each scan to the
// sink it was created with, once its acquisition gate opens; its first start-up reports the
// geometry imaging uses (the range of sample 0 and the sample count); its counters are the
// generic RadarStats (live.json's "radars"), the model's own counters listed after them.
// The LT102 is drivers/live/lt102_radar.h.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/types.h"
#include "drivers/live/device_link.h"
#include "drivers/live/fault_log.h"
#include "drivers/live/live_settings.h"

namespace uwbsar::live {

/// What a radar's start-up settled: the geometry imaging uses in a live run, the frame rate.
struct RadarSetup {
  double range_min_m = 0.0;          ///< range of sample 0
  double range_max_m = 0.0;          ///< range of the last sample
  int samples_per_scan = 0;          ///< samples of every scan
  int frame_rate_fps = 0;            ///< the radar's actual frame rate
  int frame_rate_requested_fps = 0;  ///< the rate the configuration asked for
  std::string description;           ///< one line for the log and the recording's events
};

/// The value of a model's own counter (live.json writes it with its type; give a text as
/// std::string: a string literal would convert to bool).
using RadarStatValue = std::variant<long long, double, bool, std::string>;

/// Counts of one radar over a run, for live.json and the run's log: those every radar has,
/// then the model's own (`extra`).
struct RadarStats {
  long long startups = 0;          ///< completed start-ups (settings accepted)
  long long startup_failures = 0;  ///< start-ups that failed (the link retries)
  long long config_errors = 0;     ///< start-ups refused: the radar contradicts the settings
  bool configured = false;         ///< a start-up completed
  RadarSetup setup;                ///< of the last completed start-up
  long long frames_delivered = 0;  ///< distinct frames handed to the sink (scans)
  long long frames_repeated = 0;   ///< frames received again: dropped
  long long frames_missed = 0;     ///< frames the radar acquired that never came (index gaps)
  long long frames_lost = 0;       ///< frames asked for or due that did not come in time
  long long invalid_frames = 0;    ///< frames failing validation (size, samples, CRC): dropped
  long long stamp_reanchors = 0;   ///< the stamp filter's re-anchors (start-ups not counted)
  /// The model's own counters, in the order it lists them; a name "group.key" is `key` of
  /// the object `group` in live.json (e.g. "request_to_answer_ms.p99").
  std::vector<std::pair<std::string, RadarStatValue>> extra;
  /// (arrival, stamp) of the first scans stamped (host clock): for measuring the stamp
  /// filter against an emulator's true send times.
  std::vector<std::pair<TimestampNs, TimestampNs>> stamp_trace;

  /// The model's counter `name`; null when it has none.
  const RadarStatValue* Extra(const std::string& name) const {
    for (const auto& [key, value] : extra) {
      if (key == name) return &value;
    }
    return nullptr;
  }
};

/// How long `uwbsar run` waits for a radar's first start-up before SLAM starts, and the key
/// that sets it (named when the wait runs out).
struct RadarStartupWait {
  double wait_s = 0.0;
  std::string key;
};

class RadarDevice {
 public:
  using ScanSink = std::function<void(RadarScan&& scan)>;
  using EventSink = std::function<void(const std::string& event)>;

  virtual ~RadarDevice() = default;
  /// Starts the device's own thread(s): start-up, then acquisition while the gate is open.
  virtual void Start() = 0;
  /// Asks to stop without waiting (the radars stop together; then Stop()).
  virtual void RequestStop() {}
  /// Stops (with the radar's own stop command where it has one); no scan reaches the sink
  /// after it returns. Idempotent.
  virtual void Stop() = 0;
  /// The device is reachable now (the status LED is on while every device is). Any thread.
  virtual bool connected() const = 0;
  /// Waits up to `timeout_s` for the first start-up: true with `setup` when it finished;
  /// false with `error` set when the radar refused its configuration, or empty `error` on
  /// timeout. Any thread.
  virtual bool WaitConfigured(double timeout_s, RadarSetup* setup, std::string* error) = 0;
  virtual RadarStartupWait startup_wait() const = 0;
  /// Scans handed to the sink so far. Any thread.
  virtual long long scans() const = 0;
  /// After Stop.
  virtual RadarStats stats() const = 0;
};

/// What a radar is created with (drivers/live/radar_driver_factory.h).
struct RadarDeviceArgs {
  std::string name;    ///< labels faults and events ("radar left")
  int sensor_id = 0;   ///< radars[sensor_id]: the scans' sensor id
  std::string device;  ///< live.radar_devices[sensor_id]
  LinkPolicy link;     ///< a serial link's policy (baud: live.radar_baud)
  LiveSettings settings;
  FaultLog* faults = nullptr;
  RadarDevice::ScanSink sink;
  RadarDevice::EventSink events;
  /// Host-clock stamps running `clock_scale` times wall time; empty: the sink stamps at
  /// arrival (scan.stamp_ns = 0).
  std::function<TimestampNs()> clock;
  double clock_scale = 1.0;
  /// Frames are acquired only while it returns true (empty: always): the serial source opens
  /// it once odometry flows, so no scan precedes the first pose.
  std::function<bool()> acquisition_gate;
  /// Power-cycles the radar (GPIO); empty: not wired.
  std::function<void()> power_cycle;
};

}  // namespace uwbsar::live
