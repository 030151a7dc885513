// The SLAM half of `uwbsar run` (slam/live/live_runner.h): the feeding thread takes messages
// from the Dispatcher and feeds the SlamSystem (which images on this thread and does the
// keyframe work on its own), measuring each scan's latency from arrival to its inclusion
// in the open tile; the snapshot thread rewrites the map outputs every
// live.snapshot_period_s from a copy of the SLAM state taken under the SlamSystem's state
// lock (CaptureMapState, linear in keyframes), rendering and writing after releasing it:
// the feeding thread never waits for a snapshot, the keyframe thread only for the copy.
// With a saved map (LiveRunOptions::localize_in) the feeding thread feeds a
// LocalizePipeline instead (slam/localization/localize_pipeline.h: the map is fixed, nothing is
// added to it) and the snapshots write the localisation outputs (WriteLocalizeOutputs).
#pragma once

#include <atomic>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "backend/incremental_mosaic.h"
#include "slam/app_config.h"
#include "slam/live/live_recorder.h"
#include "slam/live/live_runner.h"
#include "slam/localization/localize_pipeline.h"

namespace uwbsar::slam {

class Processor {
 public:
  /// Optional hooks on the snapshot thread (e.g. ROS 2 publishers): `after_snapshot`
  /// runs after each snapshot with the state it was written from (no lock held);
  /// `tick` every 20 ms.
  /// `after_localize` replaces `after_snapshot` when localising in a saved map.
  struct Hooks {
    std::function<void(const MapState& state, const MapOutputs& outputs)> after_snapshot;
    std::function<void()> tick;
    std::function<void(const LocalizeRun& run)> after_localize;
    /// Once, after Finish() and the final snapshot: the run's last pose with its final
    /// correction (the ticks may have published the last odometry with an older one).
    std::function<void()> final_pose;
  };

  /// With `localize_map` (outliving the processor): localisation in that map, no mapping.
  Processor(const Config& config, const LiveRunOptions& options, Dispatcher* dispatcher,
            const SessionData* localize_map = nullptr);
  void set_hooks(Hooks hooks) { hooks_ = std::move(hooks); }

  /// Feeds SLAM until `stop` is set and the queue is empty.
  void Loop(const std::atomic<bool>& stop);
  /// Writes a snapshot every live.snapshot_period_s (and calls the tick hook) until `stop`.
  void SnapshotLoop(const std::atomic<bool>& stop);
  /// Writes the outputs of the state so far (not on the feeding thread).
  void Snapshot();
  /// After Finish() and the final Snapshot(): the final_pose hook.
  void PublishFinalPose() {
    if (hooks_.final_pose) hooks_.final_pose();
  }
  /// After both threads stopped: the run with its last counters and ground truth.
  MapRun FinalRun();

  /// After both threads stopped: flushes SLAM (or the localisation) and solves a last time.
  void Finish();
  /// Mapping only (not when localising).
  SlamSystem& slam() { return *run_.slam; }
  bool localizing() const { return localize_ != nullptr; }
  /// Localising: the run so far with its processing time and ground truth.
  LocalizeRun LocalizeResult();
  /// The map <- odometry correction at `stamp_ns` (any thread): SLAM's, interpolated
  /// between keyframes; localising, the latest fix's; none before the first keyframe / fix.
  std::optional<Pose2> CorrectionAt(TimestampNs stamp_ns);
  /// The keyframe thread's longest wait for the state lock (0 when localising).
  double keyframe_lock_wait_max_s() const;
  long long odometry_messages();
  /// The last odometry sample fed to SLAM (any thread).
  std::optional<OdometrySample> LatestOdometry();
  std::vector<double>& latencies_ms() { return latencies_ms_; }
  int snapshots() const { return snapshots_; }
  const MapOutputs& last_outputs() const { return last_outputs_; }
  /// Localising: summary.json of the last snapshot (null before one).
  const nlohmann::json& last_localize_summary() const { return last_localize_summary_; }
  double snapshot_max_s() const { return snapshot_max_s_; }
  /// Every snapshot's duration (copy, render and write), seconds.
  const std::vector<double>& snapshot_s() const { return snapshot_s_; }
  /// The longest time a snapshot held (or waited for) the SLAM state lock.
  double snapshot_lock_max_s() const { return snapshot_lock_max_s_; }

 private:
  void Process(const LiveMessage& msg);
  void SnapshotLocalize();

  const Config& config_;
  const LiveRunOptions& options_;
  Dispatcher* dispatcher_;
  Hooks hooks_;
  std::mutex run_mutex_;  ///< run_'s counters and latest_odometry_, read by other threads
  MapRun run_;
  std::optional<OdometrySample> latest_odometry_;
  std::deque<SteadyClock::time_point> pending_;
  long long resolved_ = 0;
  bool failed_ = false;  ///< SLAM threw: messages are no longer processed
  std::vector<double> latencies_ms_;
  SteadyClock::time_point start_;
  int snapshots_ = 0;
  double snapshot_max_s_ = 0.0;
  double snapshot_lock_max_s_ = 0.0;
  std::vector<double> snapshot_s_;
  MapOutputs last_outputs_;
  /// The map kept between snapshots (only the blocks of keyframes that changed are redone).
  IncrementalMosaic mosaic_;
  std::unique_ptr<LocalizePipeline> localize_;
  nlohmann::json last_localize_summary_;
};

/// The p-th percentile (nearest rank) of `v`; 0 when empty.
double Percentile(std::vector<double> v, double p);

}  // namespace uwbsar::slam
