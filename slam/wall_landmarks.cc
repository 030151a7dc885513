#include "slam/wall_landmarks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <set>
#include <tuple>

namespace uwbsar::slam {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The line's offset at point q (its signed distance from q along the normal, negated).
double OffsetAt(const Line2& l, const Point2& q) { return -SignedDistance(l, q); }

}  // namespace

std::vector<SeenLine> SeenLines(const std::vector<WallLineObservation>& lines,
                                double heading_anchor_rad) {
  std::vector<SeenLine> out;
  const double ux = std::cos(heading_anchor_rad), uy = std::sin(heading_anchor_rad);
  for (const WallLineObservation& w : lines) {
    SeenLine s;
    s.line_anchor = {w.normal_rad, w.offset_m};
    s.offset_std_m = w.offset_std_m;
    s.normal_std_rad = w.normal_std_rad;
    const double mid = 0.5 * (w.begin_m + w.end_m);
    const Point2 on_path{mid * ux, mid * uy};
    const double nx = std::cos(w.normal_rad), ny = std::sin(w.normal_rad);
    const double off = w.offset_m - (nx * on_path.x_m + ny * on_path.y_m);
    s.reference_anchor = {on_path.x_m + off * nx, on_path.y_m + off * ny};
    out.push_back(s);
  }
  return out;
}

bool UsesWallLandmarks(const WallProfileConfig& walls, const BackendConfig& backend) {
  const std::array<double, 3> calibration = backend.CalibrationMean();
  const bool calibrated = calibration[0] != 0.0 || calibration[1] != 0.0 || calibration[2] != 0.0;
  return walls.enabled && walls.landmarks.enabled &&
         (calibrated || !walls.landmarks.require_calibrated_base);
}

std::vector<SeenLine> SeenLines(const KeyframeProducts& products) {
  if (!products.wall_profile) return {};
  return SeenLines(products.wall_lines, products.wall_profile->heading_rad);
}

WallLandmarkTracker::Update WallLandmarkTracker::Add(const Keyframe& keyframe,
                                                     const KeyframeProducts& products) {
  const std::vector<SeenLine> lines = SeenLines(products);
  lines_seen_ += static_cast<int>(lines.size());
  return Add(keyframe.id, keyframe.T_world_anchor, lines);
}

WallLandmarkTracker::Update WallLandmarkTracker::Add(int keyframe_id, const Pose2& T_world_anchor,
                                                     const std::vector<SeenLine>& lines) {
  ++calls_;
  Update update;
  // A track ends after more than max_gap keyframes in a row that did not see its wall.
  tracks_.erase(
      std::remove_if(tracks_.begin(), tracks_.end(),
                     [&](const Track& t) { return calls_ - t.last_seen - 1 > config_.max_gap; }),
      tracks_.end());
  // Every (line, track) pair within the gates, cheapest first; each line and track used once.
  const double gate_angle_rad = config_.gate_angle_deg * kPi / 180.0;
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    const SeenLine& seen = lines[l];
    for (std::size_t t = 0; t < tracks_.size(); ++t) {
      const Line2 predicted =
          Facing(LineToFrame(T_world_anchor, tracks_[t].last_world), seen.line_anchor);
      const double angle =
          std::abs(NormalizeAngle(predicted.normal_rad - seen.line_anchor.normal_rad));
      const double offset = std::abs(OffsetAt(predicted, seen.reference_anchor) -
                                     OffsetAt(seen.line_anchor, seen.reference_anchor));
      if (angle > gate_angle_rad || offset > config_.gate_offset_m) continue;
      const double cost = angle / gate_angle_rad + offset / config_.gate_offset_m;
      pairs.emplace_back(cost, l, t);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> track_of(lines.size(), -1);
  std::vector<int> serials;
  std::vector<char> track_used(tracks_.size(), 0);
  for (const auto& [cost, l, t] : pairs) {
    if (track_of[l] >= 0 || track_used[t]) continue;
    track_of[l] = static_cast<int>(t);
    track_used[t] = 1;
  }
  for (std::size_t l = 0; l < lines.size(); ++l) {
    if (track_of[l] < 0) {
      tracks_.emplace_back();
      tracks_.back().serial = tracks_started_++;
      track_of[l] = static_cast<int>(tracks_.size()) - 1;
    }
    Track& track = tracks_[static_cast<std::size_t>(track_of[l])];
    serials.push_back(track.serial);
    const SeenLine& seen = lines[l];
    // Every sighting faces the track's first one, so that a landmark keeps one orientation.
    const Line2 world = LineToWorld(T_world_anchor, seen.line_anchor);
    const bool first = track.waiting.empty() && track.id < 0;
    const Line2 facing_world = first ? world : Facing(world, track.last_world);
    LineObservation o;
    o.node_id = keyframe_id;
    o.line_node = LineToFrame(T_world_anchor, facing_world);
    o.reference_node = seen.reference_anchor;
    o.offset_std_m = seen.offset_std_m;
    o.normal_std_rad = seen.normal_std_rad;
    track.last_world = facing_world;
    track.last_seen = calls_;
    if (track.id >= 0) {
      landmark_of_serial_[track.serial] = track.id;
      o.landmark_id = track.id;
      update.observations.push_back(o);
      continue;
    }
    track.waiting.push_back(o);
    if (static_cast<int>(track.waiting.size()) < config_.min_observations) continue;
    track.id = next_id_++;
    landmark_of_serial_[track.serial] = track.id;
    update.new_landmarks.push_back({track.id, facing_world});
    for (LineObservation& w : track.waiting) {
      w.landmark_id = track.id;
      update.observations.push_back(w);
    }
    track.waiting.clear();
  }
  recent_.emplace_back(keyframe_id, std::move(serials));
  while (recent_.size() > 16) recent_.pop_front();
  // Only the recent keyframes' tracks are asked about.
  std::set<int> live;
  for (const auto& [id, list] : recent_) live.insert(list.begin(), list.end());
  for (auto it = landmark_of_serial_.begin(); it != landmark_of_serial_.end();)
    it = live.count(it->first) ? std::next(it) : landmark_of_serial_.erase(it);
  return update;
}

bool WallLandmarkTracker::ShareLandmark(int a_id, int b_id) const {
  const std::vector<int>* a = nullptr;
  const std::vector<int>* b = nullptr;
  for (const auto& [id, list] : recent_) {
    if (id == a_id) a = &list;
    if (id == b_id) b = &list;
  }
  if (a == nullptr || b == nullptr) return false;
  for (const int serial : *a) {
    if (landmark_of_serial_.count(serial) && std::count(b->begin(), b->end(), serial)) return true;
  }
  return false;
}

}  // namespace uwbsar::slam
