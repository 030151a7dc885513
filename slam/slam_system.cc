#include "slam/slam_system.h"

#include <algorithm>
#include <chrono>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <cmath>
#include <optional>
#include <set>

#include "core/errors.h"
#include "core/log.h"
#include "core/types.h"
#include "slam/app_config.h"
#include "slam/session/place_views.h"

namespace uwbsar::slam {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Place recognition's view of the configuration, with the candidate search widening as a gyro
/// base's heading error grows with time.
PlaceRecognizerConfig RecognizerConfig(const Config& config) {
  PlaceRecognizerConfig pr(config);
  if (config.backend.odometry_model == OdometryModel::kGyro) {
    pr.place_recognition.candidates.heading_rate_sigma_radps =
        config.backend.gyro_bias_sigma_dps * M_PI / 180.0;
  }
  return pr;
}

}  // namespace

SlamSystem::SlamSystem(const Config& config)
    : config_(config),
      frontend_(std::make_unique<ImagingFrontend>(ImagingFrontendConfig(config))),
      graph_(std::make_unique<PoseGraph>(config.backend)),
      recognizer_(std::make_unique<PlaceRecognizer>(RecognizerConfig(config))),
      wall_edges_(config.place_recognition.wall_profiles),
      wall_landmarks_(config.place_recognition.wall_profiles),
      wall_landmarks_on_(UsesWallLandmarks(config.place_recognition.wall_profiles, config.backend)),
      products_(config, config.place_recognition.wall_profiles.enabled, wall_landmarks_on_),
      stillness_(config.backend),
      tiles_(static_cast<std::size_t>(config.limits.tile_cache_mb * 1024.0 * 1024.0)),
      worker_(config.slam.keyframe_thread, config.slam.keyframe_queue_size,
              [this](Work&& work) { Process(std::move(work)); }) {
  frontend_->SetOdometryObserver(
      [this](const OdometryEntry& e) { pending_odometry_.push_back(e); });
}

SlamSystem::~SlamSystem() = default;

void SlamSystem::AddOdometry(const OdometrySample& sample) {
  worker_.RethrowError();
  const auto start = Clock::now();
  frontend_->AddOdometry(sample);
  PublishFeedingState(SecondsSince(start));
  HandOver(false);
}

void SlamSystem::AddScan(const RadarScan& scan) {
  worker_.RethrowError();
  const auto start = Clock::now();
  frontend_->AddScan(scan);
  PublishFeedingState(SecondsSince(start));
  HandOver(false);
}

void SlamSystem::Finish() {
  worker_.RethrowError();
  const auto start = Clock::now();
  frontend_->Finish();
  PublishFeedingState(SecondsSince(start));
  HandOver(true);
  WaitIdle();
  std::lock_guard<std::mutex> lock(state_mutex_);
  if (const std::optional<GyroStandstill> still = stillness_.Flush()) AddStandstill(*still);
  if (graph_->NumNodes() > 0) Optimize();
  // Final state of every loop edge still in the graph (a retired keyframe's loops keep the
  // state they had when it was folded in: accepted).
  std::map<int, const EdgeReport*> by_index;
  const std::vector<EdgeReport> reports = graph_->EdgeReports();
  for (const EdgeReport& r : reports) by_index[r.index] = &r;
  for (LoopRecord& loop : loops_) {
    auto r = by_index.find(loop.edge_index);
    if (r == by_index.end()) continue;
    loop.rejected_by_backend = r->second->rejected;
    loop.chi2 = r->second->chi2;
  }
}

void SlamSystem::WaitIdle() { worker_.Drain(); }

FrontendStats SlamSystem::frontend_stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return frontend_stats_;
}

StageTimes SlamSystem::times() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  StageTimes t = keyframe_times_;
  t.imaging_s = imaging_s_;
  return t;
}

void SlamSystem::PublishFeedingState(double imaging_s) {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  imaging_s_ += imaging_s;
  frontend_stats_ = frontend_->stats();
}

void SlamSystem::HandOver(bool force) {
  // Odometry alone is handed over in batches, so that readers of odometry() see the
  // trajectory grow between keyframes without a queue item per sample.
  constexpr std::size_t kOdometryBatch = 64;
  Work work;
  work.keyframes = frontend_->TakeKeyframes();
  if (!config_.slam.keep_scan_profiles) {
    // A closed tile's image is made: its scans' range profiles (shared with the tiles still
    // open) are needed only by the exact map. Dropped here rather than after its features, a
    // keyframe waiting in the queue no longer holds them (office ring, ten laps: 4-10 MB each).
    for (Keyframe& k : work.keyframes) {
      for (ImagedScan& s : k.scans) s.profile.reset();  // the poses stay: they place the scans
    }
  }
  if (work.keyframes.empty() && pending_odometry_.size() < kOdometryBatch &&
      !(force && !pending_odometry_.empty())) {
    return;
  }
  work.odometry.swap(pending_odometry_);
  const int num_keyframes = static_cast<int>(work.keyframes.size());
  worker_.Push(std::move(work), num_keyframes);
}

void SlamSystem::Process(Work&& work) {
  {
    const auto lock = LockForKeyframeWork();
    odometry_.insert(odometry_.end(), work.odometry.begin(), work.odometry.end());
    for (const OdometryEntry& e : work.odometry) {
      const std::optional<GyroStandstill> still =
          stillness_.Add(NsToSeconds(e.stamp_ns), e.T_world_robot);
      if (still) AddStandstill(*still);
    }
  }
  for (Keyframe& k : work.keyframes) AddKeyframe(std::move(k));
#ifdef __GLIBC__
  // Hand the pages of the keyframe's freed images (a full-resolution tile, its range profiles)
  // back to the system: glibc keeps freed memory inside its heaps, and resident memory then
  // followed the largest burst of keyframes in flight rather than what the map holds (office
  // ring, ten laps: peak heap 233 MiB, resident 393 MiB). A few milliseconds per keyframe.
  if (!work.keyframes.empty()) malloc_trim(0);
#endif
}

void SlamSystem::AddKeyframe(Keyframe&& keyframe) {
  const Pose2 estimate = AddGraphNode(keyframe);
  // The long part, without the lock: only this thread uses the recognizer.
  const PlaceRecognitionResult found = recognizer_->Process(keyframe, estimate);
  const auto start = Clock::now();
  const KeyframeProducts products = Products(keyframe);
  // Walls as landmarks where a straight wall is seen, the pairwise edges elsewhere: an edge
  // between two keyframes that see one landmark would measure that wall a second time. Both
  // read the tile's wall profile, made once with its products.
  std::vector<PoseGraphEdge> walls;
  if (products.wall_profile) walls = wall_edges_.Add(keyframe, *products.wall_profile);
  WallLandmarkTracker::Update seen;
  if (wall_landmarks_on_) {
    seen = wall_landmarks_.Add(keyframe, products);  // a tile without walls counts as a gap
    walls.erase(std::remove_if(walls.begin(), walls.end(),
                               [&](const PoseGraphEdge& e) {
                                 return wall_landmarks_.ShareLandmark(e.from_id, e.to_id);
                               }),
                walls.end());
  }
  KeyframeRecord record;
  record.detected_grid = products.grid;
  record.detected = tiles_.Put(products.detected);  // out of core from here on
  if (!config_.slam.keep_tile_images) keyframe.image.release();
  keyframe.sensor_tiles.clear();  // per-radar images: only their features are kept
  const double detected_s = SecondsSince(start);
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    keyframe_times_.features_s += found.features_ms * 1e-3 + detected_s;
    keyframe_times_.matching_s += found.matching_ms * 1e-3;
  }
  const auto lock = LockForKeyframeWork();
  for (const LoopAttempt& attempt : found.attempts) AddLoop(attempt, keyframe.id);
  // Wall edges wait for the next solve a loop asks for (or Finish): solving for them alone
  // would take the place of the solve right after a ring closure, which the keyframes after it
  // need to find their own loops (their search radius is smallest then).
  for (const PoseGraphEdge& wall : walls) {
    // A wall partner retired meanwhile (another run's, never this run's recent ones) is gone.
    if (graph_->HasNode(wall.from_id) && graph_->HasNode(wall.to_id)) graph_->AddEdge(wall);
  }
  for (const auto& [id, line] : seen.new_landmarks) graph_->AddLandmark(id, line);
  for (const LineObservation& o : seen.observations) {
    if (graph_->HasNode(o.node_id)) graph_->AddLineObservation(o);
  }
  awaiting_retirement_check_.push_back(keyframe.id);
  record.keyframe = std::move(keyframe);
  keyframes_.push_back(std::move(record));
  ++keyframes_since_solve_;
  const int every = config_.slam.optimize_every_keyframes;
  if (graph_dirty_ && every > 0 && keyframes_since_solve_ >= every) Optimize();
}

void SlamSystem::AddStandstill(const GyroStandstill& still) {
  graph_->AddGyroBiasMeasurement(/*trajectory=*/0, 0.5 * (still.begin_s + still.end_s),
                                 still.bias_radps, still.sigma_radps);
  standstills_.push_back(still);
}

Pose2 SlamSystem::AddGraphNode(const Keyframe& keyframe) {
  const auto lock = LockForKeyframeWork();
  if (keyframes_.empty()) {
    graph_->AddNode(keyframe.id, keyframe.T_world_anchor, false);
    graph_->FixNode(keyframe.id);
    return keyframe.T_world_anchor;
  }
  const Keyframe& prev = keyframes_.back().keyframe;
  const Pose2 T_prev_this = Between(prev.T_world_anchor, keyframe.T_world_anchor);
  // Anchors keep the world orientation (the step's yaw is 0): the odometry calibration
  // needs the robot's own path and turn between the two tiles' middles.
  const double path_m = std::max(0.0, 0.5 * (keyframe.path_begin_m + keyframe.path_end_m) -
                                          0.5 * (prev.path_begin_m + prev.path_end_m));
  const double turn_rad =
      NormalizeAngle(keyframe.T_world_robot.yaw_rad - prev.T_world_robot.yaw_rad);
  // The node starts on the corrected trajectory (the backend applies the base's calibration).
  // Their times: a gyro base's heading error is its bias over the time between them.
  return graph_->AddOdometryNode(prev.id, keyframe.id, T_prev_this, /*trajectory=*/0, path_m,
                                 turn_rad, NsToSeconds(prev.stamp_ns),
                                 NsToSeconds(keyframe.stamp_ns));
}

void SlamSystem::AddLoop(const LoopAttempt& attempt, int keyframe_id) {
  LoopRecord loop;
  loop.query_id = attempt.query_id >= 0 ? attempt.query_id : keyframe_id;
  loop.match_id = attempt.candidate_id;
  loop.guided = attempt.guided;
  loop.by_radar = attempt.by_radar;
  loop.matches = attempt.matches;
  loop.validation = attempt.validation;
  for (auto& [kind, m] : loop.matches) {        // only the decision is kept (memory released: a
    std::vector<cv::DMatch>().swap(m.matches);  // long run holds thousands of loop records)
    std::vector<unsigned char>().swap(m.inlier);
    std::vector<cv::Point2d>().swap(m.inliers_a);
    std::vector<cv::Point2d>().swap(m.inliers_b);
  }
  if (loop.validation.accepted) {
    PoseGraphEdge edge;
    edge.from_id = attempt.candidate_id;
    edge.to_id = loop.query_id;
    edge.T_from_to = loop.validation.constraint.T_ij;
    edge.information = loop.validation.constraint.information;
    edge.kind = EdgeKind::kLoop;
    try {
      loop.edge_index = graph_->AddEdge(edge);
      graph_dirty_ = true;
    } catch (const InputError& e) {
      loop.validation.accepted = false;
      loop.validation.reason = std::string("backend refused the edge: ") + e.what();
    }
  }
  loops_.push_back(std::move(loop));
}

void SlamSystem::Optimize() {
  const auto start = Clock::now();
  last_optimization_ = graph_->Optimize();
  RetireRevisitedViews();
  for (const auto& [id, pose] : graph_->GetPoses()) recognizer_->UpdatePose(id, pose);
  ++num_solves_;
  if (config_.slam.results_mcap) {
    SolveRecord solve;
    solve.stamp_ns = odometry_.empty() ? 0 : odometry_.back().stamp_ns;
    if (!keyframes_.empty())
      solve.stamp_ns = std::max(solve.stamp_ns, keyframes_.back().keyframe.stamp_ns);
    solve.num_odometry = odometry_.size();
    solve.num_loops = loops_.size();
    solve.ids.reserve(keyframes_.size());
    solve.poses.reserve(keyframes_.size());
    for (const KeyframeRecord& k : keyframes_) {
      solve.ids.push_back(k.keyframe.id);
      solve.poses.push_back(graph_->GetPose(k.keyframe.id));
    }
    solves_.push_back(std::move(solve));
  }
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    keyframe_times_.optimization_s += SecondsSince(start);
  }
  graph_dirty_ = false;
  keyframes_since_solve_ = 0;
}

void SlamSystem::RetireRevisitedViews() {
  const PlaceViewsConfig& config = config_.slam.place_views;
  std::vector<int> queue;
  queue.swap(awaiting_retirement_check_);
  if (config.max_per_place <= 0 || queue.empty()) return;
  const std::set<int> tied = TiedByAcceptedLoops(graph_->EdgeReports());
  const std::vector<int> fixed = graph_->FixedNodes();
  const std::map<int, Pose2> poses = graph_->GetPoses();
  std::vector<PlaceView> views;
  views.reserve(keyframes_.size());
  for (const KeyframeRecord& r : keyframes_) {
    const Keyframe& k = r.keyframe;
    const Pose2& T_world_anchor = poses.at(k.id);
    PlaceView v;
    v.id = k.id;
    v.anchor_world = {T_world_anchor.x_m, T_world_anchor.y_m};
    // The anchor keeps the odometry frame's orientation: the map's correction turns the robot
    // by as much as it turns the anchor.
    v.robot_heading_rad =
        NormalizeAngle(T_world_anchor.yaw_rad - k.T_world_anchor.yaw_rad + k.T_world_robot.yaw_rad);
    v.path_mid_m = 0.5 * (k.path_begin_m + k.path_end_m);
    v.stamp = k.stamp_ns;
    v.retirable = std::find(fixed.begin(), fixed.end(), k.id) == fixed.end();
    views.push_back(v);
  }
  uwbsar::RetireRevisitedViews(&views, queue, tied, config, [this](int victim) {
    Retire(victim);
    return true;
  });
}

void SlamSystem::Retire(int id) {
  auto it = std::find_if(keyframes_.begin(), keyframes_.end(),
                         [&](const KeyframeRecord& r) { return r.keyframe.id == id; });
  RetiredKeyframe r;
  r.id = id;
  r.stamp_ns = it->keyframe.stamp_ns;
  r.T_odom_anchor = it->keyframe.T_world_anchor;
  r.T_odom_robot = it->keyframe.T_world_robot;
  r.path_begin_m = it->keyframe.path_begin_m;
  r.path_end_m = it->keyframe.path_end_m;
  const Pose2 T_world_anchor = graph_->GetPose(id);
  r.hub_id = graph_->RemoveNode(id, &r.T_hub_anchor);
  if (r.hub_id < 0) r.T_hub_anchor = T_world_anchor;
  recognizer_->Remove(id);
  keyframes_.erase(it);
  retired_.push_back(r);
}

std::map<int, Pose2> SlamSystem::KeyframePoses() const { return graph_->GetPoses(); }

std::vector<TrajectoryAnchor> SlamSystem::Anchors() const {
  const std::map<int, Pose2> poses = graph_->GetPoses();
  std::vector<TrajectoryAnchor> kept;
  kept.reserve(keyframes_.size());
  for (const KeyframeRecord& r : keyframes_) {
    kept.push_back(
        {r.keyframe.id, r.keyframe.stamp_ns, r.keyframe.T_world_anchor, poses.at(r.keyframe.id)});
  }
  const std::map<int, Pose2> folded = RetiredPoses(retired_, poses);
  std::vector<TrajectoryAnchor> retired;
  retired.reserve(retired_.size());
  for (const RetiredKeyframe& r : retired_) {
    auto p = folded.find(r.id);
    if (p != folded.end()) retired.push_back({r.id, r.stamp_ns, r.T_odom_anchor, p->second});
  }
  return MergeAnchors(std::move(kept), retired);  // sorts both by time
}

Pose2 SlamSystem::CorrectionAt(TimestampNs stamp_ns) const {
  return uwbsar::slam::CorrectionAt(Anchors(), stamp_ns);
}

std::unique_lock<std::mutex> SlamSystem::LockForKeyframeWork() {
  std::unique_lock<std::mutex> lock(state_mutex_, std::try_to_lock);
  if (lock.owns_lock()) return lock;
  const auto start = Clock::now();
  lock.lock();
  const double waited_s = SecondsSince(start);
  std::lock_guard<std::mutex> stats(stats_mutex_);  // lock order: state, then stats
  keyframe_lock_wait_max_s_ = std::max(keyframe_lock_wait_max_s_, waited_s);
  return lock;
}

double SlamSystem::keyframe_lock_wait_max_s() const {
  std::lock_guard<std::mutex> stats(stats_mutex_);
  return keyframe_lock_wait_max_s_;
}

SlamSnapshot SlamSystem::Capture() const {
  SlamSnapshot s;
  s.config = &config_;
  s.sensors = frontend_->sensors();  // fixed at construction
  s.tiles.reserve(keyframes_.size());
  for (const KeyframeRecord& k : keyframes_) {
    TileSnapshot t;
    t.id = k.keyframe.id;
    t.stamp_ns = k.keyframe.stamp_ns;
    t.T_world_anchor = k.keyframe.T_world_anchor;
    t.detected = k.detected;  // shared: never written after the keyframe is stored
    t.detected_grid = k.detected_grid;
    for (const ImagedScan& scan : k.keyframe.scans) {
      t.first_scan_ns = t.has_scans ? std::min(t.first_scan_ns, scan.stamp_ns) : scan.stamp_ns;
      t.last_scan_ns = t.has_scans ? std::max(t.last_scan_ns, scan.stamp_ns) : scan.stamp_ns;
      t.has_scans = true;
    }
    s.tiles.push_back(std::move(t));
  }
  s.poses = graph_->GetPoses();
  for (const TrajectoryAnchor& a : Anchors()) {
    if (!s.poses.count(a.id)) s.retired.push_back(a);
  }
  s.edges = graph_->Edges();
  s.fixed_ids = graph_->FixedNodes();
  s.loops = loops_;
  s.odometry = odometry_;
  s.frontend_stats = frontend_stats();
  s.times = times();
  s.last_optimization = last_optimization_;
  s.solves = solves_;
  s.num_solves = num_solves_;
  return s;
}

std::vector<std::pair<TimestampNs, Pose2>> SlamSystem::CorrectedTrajectory() const {
  const std::vector<TrajectoryAnchor> anchors = Anchors();
  std::vector<std::pair<TimestampNs, Pose2>> out;
  out.reserve(odometry_.size());
  for (const OdometryEntry& e : odometry_) {
    out.push_back({e.stamp_ns, uwbsar::slam::CorrectionAt(anchors, e.stamp_ns) * e.T_world_robot});
  }
  return out;
}

}  // namespace uwbsar::slam
