#include "slam/live/live_processor.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "core/log.h"
#include "slam/app_config.h"
#include "slam/outputs/localize_outputs.h"
#include "slam/outputs/session_capture.h"
#include "slam/session/session_file.h"

namespace uwbsar::slam {

Processor::Processor(const Config& config, const LiveRunOptions& options, Dispatcher* dispatcher,
                     const SessionData* localize_map)
    : config_(config),
      options_(options),
      dispatcher_(dispatcher),
      mosaic_(config.slam.map_resolution_m, config.slam.mosaic_redraw_px) {
  run_.input = "live run";
  if (localize_map) {
    localize_ = std::make_unique<LocalizePipeline>(*localize_map, config, run_.input);
  } else {
    // Live mode records its own bag and publishes over ROS 2; results.mcap is an offline
    // output, and its per-solve history would grow with the hours driven.
    Config slam_config = config;
    slam_config.slam.results_mcap = false;
    run_.slam = std::make_shared<SlamSystem>(slam_config);
  }
  start_ = SteadyClock::now();
}

void Processor::Finish() {
  if (localize_) {
    localize_->Finish();
  } else {
    run_.slam->Finish();
  }
}

LocalizeRun Processor::LocalizeResult() {
  LocalizeRun run = localize_->Result();
  run.processing_s = std::chrono::duration<double>(SteadyClock::now() - start_).count();
  if (run.odometry.size() >= 2) {
    run.log_duration_s = NsToSeconds(run.odometry.back().stamp_ns - run.odometry.front().stamp_ns);
  }
  if (options_.ground_truth) run.ground_truth = options_.ground_truth();
  return run;
}

std::optional<Pose2> Processor::CorrectionAt(TimestampNs stamp_ns) {
  if (localize_) return localize_->T_map_odom();
  const auto lock = run_.slam->LockState();
  return run_.slam->CorrectionAt(stamp_ns);
}

double Processor::keyframe_lock_wait_max_s() const {
  return localize_ ? 0.0 : run_.slam->keyframe_lock_wait_max_s();
}

/// Localising: the outputs of the run so far (each file atomic), then the hook.
void Processor::SnapshotLocalize() {
  const LocalizeRun run = LocalizeResult();
  if (run.keyframes.empty()) return;
  last_localize_summary_ = WriteLocalizeOutputs(run, options_.out_dir);
  ++snapshots_;
  if (hooks_.after_localize) hooks_.after_localize(run);
}

void Processor::Loop(const std::atomic<bool>& stop) {
  LiveMessage msg;
  while (true) {
    if (dispatcher_->Pop(&msg, std::chrono::milliseconds(20))) {
      if (failed_) continue;  // keep draining: the recording goes on regardless
      try {
        Process(msg);
      } catch (const std::exception& e) {
        // A SLAM failure must not take the recording down; Finish() reports it again.
        Log(LogLevel::kError, std::string("SLAM stopped: ") + e.what() +
                                  "; recording continues, map it later with uwbsar map");
        failed_ = true;
      }
    } else if (stop) {
      break;
    }
  }
}

void Processor::SnapshotLoop(const std::atomic<bool>& stop) {
  const double period_s = config_.live.snapshot_period_s;
  const auto period = std::chrono::duration<double>(period_s);
  auto next = SteadyClock::now() + period;
  while (!stop) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (hooks_.tick) hooks_.tick();
    if (period_s <= 0 || SteadyClock::now() < next) continue;
    Snapshot();
    next = SteadyClock::now() + period;
  }
}

void Processor::Snapshot() {
  const auto t0 = SteadyClock::now();
  if (localize_) {
    try {
      SnapshotLocalize();
    } catch (const std::exception& e) {
      Log(LogLevel::kWarning, std::string("snapshot not written: ") + e.what());
    }
    const double took_s = std::chrono::duration<double>(SteadyClock::now() - t0).count();
    snapshot_max_s_ = std::max(snapshot_max_s_, took_s);
    snapshot_s_.push_back(took_s);
    return;
  }
  MapRun view;  // the counters as of now, the same SlamSystem
  {
    std::lock_guard<std::mutex> lock(run_mutex_);
    view.slam = run_.slam;
    view.input = run_.input;
    view.first_stamp_ns = run_.first_stamp_ns;
    view.last_stamp_ns = run_.last_stamp_ns;
    view.messages = run_.messages;
    view.radar_messages = run_.radar_messages;
    view.odometry_messages = run_.odometry_messages;
  }
  view.processing_s = std::chrono::duration<double>(t0 - start_).count();
  if (options_.ground_truth) view.ground_truth = options_.ground_truth();
  try {
    // Only the copy is made under the state lock (time linear in keyframes, no I/O); the
    // mosaic, the report and the files are made from the copy while SLAM goes on.
    MapState state;
    SessionData session;  // session.uwbsar at every snapshot
    {
      const auto lock_start = SteadyClock::now();
      const auto lock = view.slam->LockState();
      if (view.slam->keyframes().empty()) return;
      state = CaptureMapState(view);
      session = CaptureSession(view);
      snapshot_lock_max_s_ =
          std::max(snapshot_lock_max_s_,
                   std::chrono::duration<double>(SteadyClock::now() - lock_start).count());
    }
    MapOutputStage stage(options_.out_dir);
    stage.KeepMosaic(&mosaic_);
    stage.SetExtraOutputs([&session, this](const std::string& dir) {
      WriteSession(dir + "/" + kSessionFileName, session, config_.session.lossless_tiles);
      return std::vector<std::string>{kSessionFileName};
    });
    last_outputs_ = stage.Commit(state);
    ++snapshots_;
    if (hooks_.after_snapshot) hooks_.after_snapshot(state, last_outputs_);
  } catch (const std::exception& e) {
    Log(LogLevel::kWarning, std::string("snapshot not written: ") + e.what());
  }
  const double took_s = std::chrono::duration<double>(SteadyClock::now() - t0).count();
  snapshot_max_s_ = std::max(snapshot_max_s_, took_s);
  snapshot_s_.push_back(took_s);
}

MapRun Processor::FinalRun() {
  run_.processing_s = std::chrono::duration<double>(SteadyClock::now() - start_).count();
  if (options_.ground_truth) run_.ground_truth = options_.ground_truth();
  return std::move(run_);
}

long long Processor::odometry_messages() {
  std::lock_guard<std::mutex> lock(run_mutex_);
  return run_.odometry_messages;
}

std::optional<OdometrySample> Processor::LatestOdometry() {
  std::lock_guard<std::mutex> lock(run_mutex_);
  return latest_odometry_;
}

void Processor::Process(const LiveMessage& msg) {
  // Feed() in two halves: the counters under run_mutex_ (the snapshot thread reads them),
  // SLAM without it.
  {
    std::lock_guard<std::mutex> lock(run_mutex_);
    CountMessage(&run_, msg);
    if (msg.kind == Message::Kind::kOdometry) latest_odometry_ = msg.odometry;
  }
  if (msg.kind == Message::Kind::kRadarScan) pending_.push_back(msg.arrival);
  if (localize_) {
    FeedScanOrOdometry(*localize_, msg);
  } else {
    FeedSlam(*run_.slam, msg);
  }
  // A scan is resolved once the frontend imaged, gated or rejected it (it may wait for
  // the odometry after it); resolution is in arrival order.
  const FrontendStats s = localize_ ? localize_->frontend_stats() : run_.slam->frontend_stats();
  const long long resolved = s.scans_imaged + s.scans_gated + s.scans_rejected();
  const auto now = SteadyClock::now();
  while (resolved_ < resolved && !pending_.empty()) {
    latencies_ms_.push_back(
        std::chrono::duration<double, std::milli>(now - pending_.front()).count());
    pending_.pop_front();
    ++resolved_;
  }
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(v.size()))) - 1;
  return v[std::min(k, v.size() - 1)];
}

}  // namespace uwbsar::slam
