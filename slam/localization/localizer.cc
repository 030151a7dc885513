#include "slam/localization/localizer.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "backend/pose_graph.h"
#include "frontend/place_recognition/feature_matcher.h"
#include "frontend/place_recognition/loop_validator.h"

namespace uwbsar {

const char* LocalizeStatusName(LocalizeStatus status) {
  switch (status) {
    case LocalizeStatus::kTracking:
      return "tracking";
    case LocalizeStatus::kLost:
      return "lost";
    case LocalizeStatus::kRelocalised:
      return "relocalised";
  }
  return "lost";
}

namespace {

bool UsesMapWalls(const SessionSettings& config) {
  const WallProfileConfig& walls = config.place_recognition.wall_profiles;
  return walls.enabled && walls.landmarks.enabled;
}

bool Agree(const Pose2& x, const Pose2& y, const SessionConfig& c) {
  const Pose2 d = Between(x, y);
  return std::hypot(d.x_m, d.y_m) <= c.connect_agree_m &&
         std::abs(NormalizeAngle(d.yaw_rad)) <= c.connect_agree_deg * M_PI / 180.0;
}

}  // namespace

Localizer::Localizer(const SessionData& map, const SessionSettings& config)
    : map_(map),
      config_(config),
      pr_(AtFeatureResolution(config.place_recognition, FeatureDownsampling(config))) {
  if (UsesMapWalls(config)) {
    map_walls_ = slam::MapWalls(map, config.place_recognition.wall_profiles.landmarks,
                                2.0 * config.keyframe.tile_length_m);
  }
}

const LocalizedKeyframe& Localizer::Add(const KeyframeFeatures& features,
                                        const Pose2& T_odom_anchor, TimestampNs stamp_ns,
                                        double path_end_m, const std::vector<slam::SeenLine>& walls,
                                        const RegistrationImage& image) {
  const SessionConfig& sc = config_.session;
  LocalizedKeyframe k;
  k.id = features.id;
  k.stamp_ns = stamp_ns;
  k.path_end_m = path_end_m;
  k.T_odom_anchor = T_odom_anchor;
  const int index = static_cast<int>(keyframes_.size());
  if (keyframes_.empty()) path_at_last_loop_m_ = path_end_m;
  const bool was_lost = placed_ && path_end_m - path_at_last_loop_m_ > sc.localize_lost_after_m;
  const bool global = !placed_ || was_lost;

  const std::vector<Loop> found = MatchMap(features, T_odom_anchor, index, global, &k.candidates);

  keyframes_.push_back(k);
  LocalizedKeyframe& out = keyframes_.back();
  std::vector<Loop> used;
  if (global) {
    used = Place(found, &out);
  } else {
    // Tracking: keep the loops that agree with the estimate (a false one would not).
    SessionConfig gate = sc;
    gate.connect_agree_m *= 2;
    gate.connect_agree_deg *= 2;
    for (const Loop& l : found) {
      if (Agree(l.T_map_odom, T_map_odom_, gate)) used.push_back(l);
    }
    out.status = LocalizeStatus::kTracking;
  }
  out.loops = static_cast<int>(used.size());
  if (placed_ && UsesRegistration() && !image.empty()) {
    const std::vector<Loop> registered =
        RegisterWithMap(image, features.centre_anchor, T_odom_anchor, index);
    out.registrations = static_cast<int>(registered.size());
    used.insert(used.end(), registered.begin(), registered.end());
  }
  if (!used.empty()) {
    path_at_last_loop_m_ = path_end_m;
    for (const Loop& l : used) window_loops_.push_back(l);
  }
  if (placed_) {
    for (const LineObservation& o : map_walls_.Observe(walls, T_map_odom_ * T_odom_anchor, index)) {
      window_walls_.push_back(o);
      ++out.walls;
    }
  }
  if (!used.empty() || out.walls > 0) SolveWindow();
  out.T_map_anchor = T_map_odom_ * T_odom_anchor;
  out.placed = placed_;
  return out;
}

std::vector<Localizer::Loop> Localizer::MatchMap(const KeyframeFeatures& features,
                                                 const Pose2& T_odom_anchor, int index, bool global,
                                                 int* candidates) const {
  const SessionConfig& sc = config_.session;
  // Candidates: every map keyframe (global), or those near the estimate.
  const Point2 centre = T_map_odom_ * (T_odom_anchor * features.centre_anchor);
  std::vector<Loop> found;
  for (const SessionKeyframe& m : map_.keyframes) {
    if (!global) {
      const Point2 q = m.T_map_anchor * m.features.centre_anchor;
      if (std::hypot(q.x_m - centre.x_m, q.y_m - centre.y_m) > sc.search_radius_m) continue;
    }
    ++*candidates;
    const DetectorMap<MatchResult> matches = MatchDetectorPair(m.features, features, pr_);
    const LoopValidation v =
        ValidateLoop(m.id, m.features.grid, features.id, features.grid, matches, pr_.validation);
    if (!v.accepted) continue;
    Loop l;
    l.map_id = m.id;
    l.keyframe_index = index;
    l.T_ij = v.constraint.T_ij;
    l.information = v.constraint.information;
    l.T_map_odom = m.T_map_anchor * l.T_ij * T_odom_anchor.Inverse();
    found.push_back(l);
  }
  return found;
}

std::vector<Localizer::Loop> Localizer::Place(const std::vector<Loop>& found,
                                              LocalizedKeyframe* out) {
  const SessionConfig& sc = config_.session;
  std::vector<Loop> used;
  // (Re-)placement: enough loops, over the recent keyframes, that agree with each other.
  for (const Loop& l : found) unplaced_.push_back(l);
  for (const Loop& l : found) {
    std::vector<Loop> agreeing;
    for (const Loop& o : unplaced_) {
      if (Agree(o.T_map_odom, l.T_map_odom, sc)) agreeing.push_back(o);
    }
    if (static_cast<int>(agreeing.size()) >= sc.connect_min_loops) {
      used = agreeing;
      T_map_odom_ = l.T_map_odom;
      break;
    }
  }
  if (!used.empty()) {
    placed_ = true;
    unplaced_.clear();
    window_loops_.clear();
    out->status = LocalizeStatus::kRelocalised;
  } else {
    out->status = LocalizeStatus::kLost;
  }
  return used;
}

std::vector<Localizer::Loop> Localizer::RegisterWithMap(const RegistrationImage& image,
                                                        const Point2& centre_anchor,
                                                        const Pose2& T_odom_anchor, int index) {
  const MapRegistrationConfig& rc = pr_.registration;
  const Pose2 T_map_anchor = T_map_odom_ * T_odom_anchor;
  const Point2 centre = T_map_anchor * centre_anchor;
  // The map tiles whose centres lie nearest the keyframe's predicted centre.
  std::vector<std::pair<double, const SessionKeyframe*>> near;
  for (const SessionKeyframe& m : map_.keyframes) {
    if (m.detected.empty()) continue;
    const Point2 q = m.T_map_anchor * m.features.centre_anchor;
    const double d = std::hypot(q.x_m - centre.x_m, q.y_m - centre.y_m);
    if (d <= rc.max_centre_distance_m) near.emplace_back(d, &m);
  }
  const std::size_t n = std::min(near.size(), static_cast<std::size_t>(rc.max_map_tiles));
  std::partial_sort(near.begin(), near.begin() + static_cast<long>(n), near.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Loop> found;
  for (std::size_t k = 0; k < n; ++k) {
    const SessionKeyframe& m = *near[k].second;
    const MapRegistration r =
        RegisterTiles(MapImage(m), image, Between(m.T_map_anchor, T_map_anchor), rc);
    if (!r.accepted) continue;
    Loop l;
    l.map_id = m.id;
    l.keyframe_index = index;
    l.T_ij = r.T_ab;
    l.information = r.information;
    l.T_map_odom = m.T_map_anchor * l.T_ij * T_odom_anchor.Inverse();
    found.push_back(l);
  }
  return found;
}

const RegistrationImage& Localizer::MapImage(const SessionKeyframe& m) {
  constexpr std::size_t kCachedImages = 64;  // a few tiles' worth of path around the robot
  auto it = map_images_.find(m.id);
  if (it != map_images_.end()) {
    map_image_order_.splice(map_image_order_.begin(), map_image_order_, it->second.second);
    return it->second.first;
  }
  if (map_images_.size() >= kCachedImages) {
    map_images_.erase(map_image_order_.back());
    map_image_order_.pop_back();
  }
  map_image_order_.push_front(m.id);
  auto& entry = map_images_[m.id];
  entry.first = MakeRegistrationImage(m.detected.Load(), m.detected_grid, pr_.registration);
  entry.second = map_image_order_.begin();
  return entry.first;
}

void Localizer::SolveWindow() {
  // The window: the last localize_window_keyframes keyframes, chained by odometry, tied to
  // the fixed map keyframes by their loops. The newest keyframe's solution sets T_map_odom.
  const int last = static_cast<int>(keyframes_.size()) - 1;
  const int first = std::max(0, last - config_.session.localize_window_keyframes + 1);
  while (!window_loops_.empty() && window_loops_.front().keyframe_index < first) {
    window_loops_.pop_front();
  }
  while (!window_walls_.empty() && window_walls_.front().node_id < first) {
    window_walls_.pop_front();
  }
  BackendConfig backend = config_.backend;
  backend.min_loop_support = 0;  // the loops passed the gate against the estimate already
  PoseGraph graph(backend);
  constexpr int kMapIdBase = 1 << 30;  // map nodes, kept apart from the window's indices
  for (int i = first; i <= last; ++i) {
    graph.AddNode(i, T_map_odom_ * keyframes_[i].T_odom_anchor, false);
    if (i > first) {
      graph.AddOdometryEdge(i - 1, i,
                            Between(keyframes_[i - 1].T_odom_anchor, keyframes_[i].T_odom_anchor));
    }
  }
  for (const Loop& l : window_loops_) {
    const int node = kMapIdBase + l.map_id;
    if (!graph.HasNode(node)) {
      graph.AddNode(node, map_.Find(l.map_id)->T_map_anchor, false);
      graph.FixNode(node);
    }
    PoseGraphEdge e;
    e.from_id = node;
    e.to_id = l.keyframe_index;
    e.T_from_to = l.T_ij;
    e.information = l.information;
    e.kind = EdgeKind::kLoop;
    graph.AddEdge(e);
  }
  // The map's walls stay where the map has them. Without a loop in the window its first
  // keyframe holds the gauge (where the last solution put it): walls give no position along.
  std::set<int> walls_added;
  for (const LineObservation& o : window_walls_) {
    if (walls_added.insert(o.landmark_id).second) {
      graph.AddLandmark(o.landmark_id, map_walls_.Line(o.landmark_id), /*fixed=*/true);
    }
    graph.AddLineObservation(o);
  }
  graph.Optimize();
  T_map_odom_ = graph.GetPose(last) * keyframes_[last].T_odom_anchor.Inverse();
}

}  // namespace uwbsar
