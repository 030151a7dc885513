#include "slam/localization/localize_pipeline.h"

#include "frontend/place_recognition/place_recognizer.h"
#include "slam/wall_landmarks.h"

namespace uwbsar::slam {

LocalizePipeline::LocalizePipeline(const SessionData& map, const Config& config, std::string input)
    : config_(config),
      frontend_(config),
      localizer_(map, config),
      products_(config, localizer_.UsesWalls(), localizer_.UsesWalls()),
      worker_(config.slam.keyframe_thread, config.slam.keyframe_queue_size,
              [this](Keyframe&& k) { Localize(k); }) {
  run_.input = std::move(input);
  frontend_.SetOdometryObserver([this](const OdometryEntry& e) {
    std::lock_guard<std::mutex> lock(result_mutex_);
    run_.odometry.push_back(e);
  });
}

void LocalizePipeline::AddOdometry(const OdometrySample& sample) {
  worker_.RethrowError();
  frontend_.AddOdometry(sample);
  HandOver();
}

void LocalizePipeline::AddScan(const RadarScan& scan) {
  worker_.RethrowError();
  frontend_.AddScan(scan);
  HandOver();
}

void LocalizePipeline::Finish() {
  worker_.RethrowError();
  frontend_.Finish();
  HandOver();
  worker_.Drain();
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
  for (Keyframe& k : frontend_.TakeKeyframes()) worker_.Push(std::move(k), 1);
}

// The features and the matching (the long part) without the result lock.
void LocalizePipeline::Localize(const Keyframe& k) {
  const KeyframeFeatures f = ExtractKeyframeFeatures(k, config_);
  // The detected tile only for the map's walls and the registration against the map's tiles.
  std::vector<SeenLine> walls;
  RegistrationImage image;
  if (localizer_.UsesWalls() || localizer_.UsesRegistration()) {
    const KeyframeProducts p = Products(k);
    if (localizer_.UsesWalls() && k.complete) walls = SeenLines(p);
    if (localizer_.UsesRegistration()) {
      image = MakeRegistrationImage(p.detected, p.grid, config_.place_recognition.registration);
    }
  }
  const LocalizedKeyframe l =
      localizer_.Add(f, k.T_world_anchor, k.stamp_ns, k.path_end_m, walls, image);
  std::lock_guard<std::mutex> lock(result_mutex_);
  run_.keyframes.push_back(l);
  if (l.placed) T_map_odom_ = l.T_map_anchor * l.T_odom_anchor.Inverse();
  if (run_.first_fix < 0 && l.placed) {
    run_.first_fix = static_cast<int>(run_.keyframes.size()) - 1;
    run_.first_fix_path_m = k.path_end_m - (run_.odometry.empty() ? 0 : run_.odometry[0].path_m);
    // The tile closes at its last scan: that is when the fix is known.
    const TimestampNs t = k.scans.empty() ? k.stamp_ns : k.scans.back().stamp_ns;
    run_.first_fix_stamp_ns = t;
    run_.first_fix_time_s =
        run_.odometry.empty() ? 0 : NsToSeconds(t - run_.odometry.front().stamp_ns);
  }
}

}  // namespace uwbsar::slam
