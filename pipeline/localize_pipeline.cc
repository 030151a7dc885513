#include "pipeline/localize_pipeline.h"

#include "frontend/place_recognition/place_recognizer.h"

namespace uwbsar::pipeline {

LocalizePipeline::LocalizePipeline(const SessionData& map, const Config& config, std::string input)
    : config_(config), frontend_(config), localizer_(map, config) {
  run_.input = std::move(input);
  frontend_.SetOdometryObserver([this](const OdometryEntry& e) {
    std::lock_guard<std::mutex> lock(result_mutex_);
    run_.odometry.push_back(e);
  });
  if (config_.slam.keyframe_thread) worker_ = std::thread([this] { WorkerLoop(); });
}

LocalizePipeline::~LocalizePipeline() {
  if (!worker_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    stopping_ = true;
  }
  queue_changed_.notify_all();
  worker_.join();
}

void LocalizePipeline::AddOdometry(const OdometrySample& sample) {
  RethrowWorkerError();
  frontend_.AddOdometry(sample);
  HandOver();
}

void LocalizePipeline::AddScan(const RadarScan& scan) {
  RethrowWorkerError();
  frontend_.AddScan(scan);
  HandOver();
}

void LocalizePipeline::Finish() {
  RethrowWorkerError();
  frontend_.Finish();
  HandOver();
  if (worker_.joinable()) {
    std::unique_lock<std::mutex> lock(queue_mutex_);
    queue_changed_.wait(lock, [this] { return (queue_.empty() && !busy_) || worker_error_; });
  }
  RethrowWorkerError();
}

FrontendStats LocalizePipeline::frontend_stats() const {
  std::lock_guard<std::mutex> lock(result_mutex_);
  return frontend_stats_;
}

LocalizeRun LocalizePipeline::Result() const {
  std::lock_guard<std::mutex> lock(result_mutex_);
  return run_;
}

std::optional<Pose2> LocalizePipeline::T_map_odom() const {
  std::lock_guard<std::mutex> lock(result_mutex_);
  return T_map_odom_;
}

void LocalizePipeline::HandOver() {
  {
    std::lock_guard<std::mutex> lock(result_mutex_);
    frontend_stats_ = frontend_.stats();
  }
  std::vector<Keyframe> keyframes = frontend_.TakeKeyframes();
  if (keyframes.empty()) return;
  if (!worker_.joinable()) {
    for (const Keyframe& k : keyframes) Localize(k);
    return;
  }
  for (Keyframe& k : keyframes) {
    std::unique_lock<std::mutex> lock(queue_mutex_);
    // Back-pressure: a full queue makes the feeder wait (bounded memory offline).
    queue_changed_.wait(lock, [this] {
      return static_cast<int>(queue_.size()) < config_.slam.keyframe_queue_size || worker_error_;
    });
    if (worker_error_) break;
    queue_.push_back(std::move(k));
    lock.unlock();
    queue_changed_.notify_all();
  }
  RethrowWorkerError();
}

void LocalizePipeline::WorkerLoop() {
  while (true) {
    Keyframe keyframe;
    {
      std::unique_lock<std::mutex> lock(queue_mutex_);
      queue_changed_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping with nothing left
      keyframe = std::move(queue_.front());
      queue_.pop_front();
      busy_ = true;
    }
    queue_changed_.notify_all();
    try {
      Localize(keyframe);
    } catch (...) {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      worker_error_ = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      busy_ = false;
    }
    queue_changed_.notify_all();
  }
}

// The features and the matching (the long part) without the result lock.
void LocalizePipeline::Localize(const Keyframe& k) {
  const KeyframeFeatures f = ExtractKeyframeFeatures(k, config_);
  const LocalizedKeyframe l = localizer_.Add(f, k.T_world_anchor, k.stamp_ns, k.path_end_m);
  std::lock_guard<std::mutex> lock(result_mutex_);
  run_.keyframes.push_back(l);
  if (l.placed) T_map_odom_ = l.T_map_anchor * l.T_odom_anchor.Inverse();
  if (run_.first_fix < 0 && l.placed) {
    run_.first_fix = static_cast<int>(run_.keyframes.size()) - 1;
    run_.first_fix_path_m = k.path_end_m - (run_.odometry.empty() ? 0 : run_.odometry[0].path_m);
    // The tile closes at its last scan: that is when the fix is known.
    const TimestampNs t = k.scans.empty() ? k.stamp_ns : k.scans.back().stamp_ns;
    run_.first_fix_time_s =
        run_.odometry.empty() ? 0 : NsToSeconds(t - run_.odometry.front().stamp_ns);
  }
}

void LocalizePipeline::RethrowWorkerError() {
  std::exception_ptr error;
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    error = worker_error_;
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace uwbsar::pipeline
