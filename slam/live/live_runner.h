// `uwbsar run`: SLAM live on the robot. A source (slam/live/live_source.h: the drivers of
// the radars (live.radar_model: two LT102 on serial by default) and of the Kobuki base,
// stamping every message on the host clock; or a ROS 2 robot over DDS, keeping the publisher's
// stamps) hands messages from its own threads to a dispatcher (slam/live/live_recorder.h), which
// passes each to the recorder (a ROS 2 bag, unbounded queue: nothing is ever dropped from the
// recording, made durable at least every live.recording_flush_period_s) and to the SLAM feeding
// thread through a bounded queue (when SLAM falls behind the oldest waiting messages are
// dropped from processing and counted). The feeding thread (slam/live/live_processor.h) runs
// the same SlamSystem as `uwbsar map` and measures each scan's latency from arrival to
// its inclusion in the open tile; a snapshot thread rewrites the map outputs atomically
// every live.snapshot_period_s. Stop (SIGINT/SIGTERM, or the options' stop flag): the
// source stops, the queue is drained, the graph is solved a last time, the final outputs
// and live.json are written and the recording is closed. With serial devices the radars
// start (and report their range) before SLAM is built: the echoed range, not the YAML,
// sets each radar's range of sample 0 and sample count for imaging. With
// LiveRunOptions::localize_in the run localises in a saved map instead of mapping
// (slam/live/live_processor.h); it records and publishes as a mapping run does.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "drivers/live/gpio.h"
#include "drivers/live/radar_device.h"
#include "slam/app_config.h"
#include "slam/localization/localize_job.h"
#include "slam/map_job.h"
#include "slam/outputs/map_outputs.h"

namespace uwbsar::slam {

struct LiveRunOptions {
  std::string source = "serial";  ///< serial (the robot's devices) or ros2 (DDS)
  std::string out_dir;            ///< snapshots, final outputs, live.json
  std::string recording_dir;      ///< the bag; empty = <out_dir>/rosbag2_<date>-<time>
  double time_scale = 1.0;        ///< host stamps advance this much faster than wall time (tests)
  /// The GPIO chip; null = from live.gpio_chip (libgpiod, or none when it is empty).
  std::unique_ptr<live::GpioChip> gpio;
  const std::atomic<bool>* stop = nullptr;  ///< the run ends when it becomes true
  /// Called on the SLAM thread before each snapshot: ground truth for the summary (tests).
  std::function<std::vector<OdometrySample>()> ground_truth;
  bool quiet = false;
  /// A saved session (folder or session.uwbsar): localise in it instead of mapping (the
  /// map is fixed; snapshots write trajectory.tum, localize.csv and summary.json).
  std::string localize_in;
  /// Replace a saved map (session.uwbsar) that out_dir already holds; refused otherwise.
  bool overwrite = false;
};

struct LiveRunResult {
  MapRun run;  ///< localising: the message counters only (no SlamSystem)
  MapOutputs outputs;
  bool localized = false;           ///< LiveRunOptions::localize_in was set
  LocalizeRun localize;             ///< localising: the run in the saved map's frame
  nlohmann::json localize_summary;  ///< localising: summary.json as last written
  std::string recording_path;
  long long scans_received = 0;
  long long odometry_received = 0;
  long long events_recorded = 0;
  long long recorded_messages = 0;
  long long dropped_from_processing = 0;
  long long latency_samples = 0;
  double latency_p50_ms = 0.0;
  double latency_p99_ms = 0.0;
  double latency_max_ms = 0.0;
  int snapshots = 0;
  double snapshot_max_s = 0.0;
  double snapshot_p50_s = 0.0;
  /// The longest a snapshot held the SLAM state lock (the copy), and the longest the
  /// keyframe thread waited for that lock over the run.
  double snapshot_lock_max_s = 0.0;
  double keyframe_lock_wait_max_s = 0.0;
  std::map<std::string, long long> faults;
  /// Serial: each radar's counts (start-ups, frames delivered, repeated, missed, lost, the
  /// echoed range; then the model's own, e.g. the LT102's `d` requests and request-to-answer
  /// times), by name ("radar left").
  std::vector<std::pair<std::string, live::RadarStats>> radars;
};

/// Locks options.out_dir for this process (slam/outputs/map_outputs.h LockOutputFolder) and
/// refuses a folder the run must not write: a saved map's folder when localising, one holding
/// a saved map when mapping without options.overwrite. RunLive does this first; a caller that
/// prepares devices inside out_dir (`run --emulate`) calls it before them.
FolderLock LockLiveOutputFolder(const LiveRunOptions& options);

/// Runs until the stop flag is set. Throws InputError / GpioError on start-up problems
/// (device list not matching the radars, GPIO chip or line missing, DDS refusing).
LiveRunResult RunLive(const Config& config, LiveRunOptions options);

}  // namespace uwbsar::slam
