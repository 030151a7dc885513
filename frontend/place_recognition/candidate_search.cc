#include "frontend/place_recognition/candidate_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace uwbsar {

KeyframeIndex::KeyframeIndex(double cell_m) : cell_m_(cell_m > 0 ? cell_m : 1.0) {}

long long KeyframeIndex::CellOf(double v) const {
  return static_cast<long long>(std::floor(v / cell_m_));
}

KeyframeIndex::CellKey KeyframeIndex::KeyOf(long long cx, long long cy) const {
  // 32 bits per axis: cells of 1 m cover +-2e9 m, far beyond any run.
  return static_cast<CellKey>((static_cast<std::uint64_t>(cx) << 32) ^
                              (static_cast<std::uint64_t>(cy) & 0xffffffffULL));
}

void KeyframeIndex::Upsert(int id, const Point2& position_world, double path_begin_m) {
  const CellKey key = KeyOf(CellOf(position_world.x_m), CellOf(position_world.y_m));
  auto it = entries_.find(id);
  if (it != entries_.end()) {
    std::vector<int>& old = cells_[it->second.cell];
    old.erase(std::remove(old.begin(), old.end(), id), old.end());
    if (old.empty()) cells_.erase(it->second.cell);
  }
  entries_[id] = Entry{position_world, path_begin_m, key};
  cells_[key].push_back(id);
}

void KeyframeIndex::Remove(int id) {
  auto it = entries_.find(id);
  if (it == entries_.end()) return;
  std::vector<int>& cell = cells_[it->second.cell];
  cell.erase(std::remove(cell.begin(), cell.end(), id), cell.end());
  if (cell.empty()) cells_.erase(it->second.cell);
  entries_.erase(it);
}

std::vector<KeyframeIndex::Hit> KeyframeIndex::Within(const Point2& p, double radius_m) const {
  std::vector<Hit> out;
  if (!(radius_m >= 0) || !std::isfinite(p.x_m) || !std::isfinite(p.y_m)) return out;
  const long long x0 = CellOf(p.x_m - radius_m), x1 = CellOf(p.x_m + radius_m);
  const long long y0 = CellOf(p.y_m - radius_m), y1 = CellOf(p.y_m + radius_m);
  // A radius much larger than the map would visit many empty cells: scan entries instead.
  if (static_cast<double>(x1 - x0 + 1) * static_cast<double>(y1 - y0 + 1) >
      4.0 * static_cast<double>(entries_.size()) + 16.0) {
    for (const Hit& h : All(p)) {
      if (h.distance_m <= radius_m) out.push_back(h);
    }
    return out;
  }
  for (long long cx = x0; cx <= x1; ++cx) {
    for (long long cy = y0; cy <= y1; ++cy) {
      auto cell = cells_.find(KeyOf(cx, cy));
      if (cell == cells_.end()) continue;
      for (int id : cell->second) {
        const Entry& e = entries_.at(id);
        const double d = std::hypot(e.position.x_m - p.x_m, e.position.y_m - p.y_m);
        if (d <= radius_m) out.push_back({id, d, e.path_begin_m});
      }
    }
  }
  return out;
}

std::vector<KeyframeIndex::Hit> KeyframeIndex::All(const Point2& p) const {
  std::vector<Hit> out;
  out.reserve(entries_.size());
  for (const auto& [id, e] : entries_) {
    out.push_back({id, std::hypot(e.position.x_m - p.x_m, e.position.y_m - p.y_m), e.path_begin_m});
  }
  return out;
}

double SearchRadius(const CandidateSearchConfig& c, double travelled_since_loop_m,
                    double seconds_since_loop_s) {
  const double d = std::max(0.0, travelled_since_loop_m);
  const double t = std::isfinite(seconds_since_loop_s) ? std::max(0.0, seconds_since_loop_s) : 0.0;
  const double heading_m = 3.0 * c.heading_rate_sigma_radps * d * t / 2.0;
  return std::min(c.max_radius_m, c.base_radius_m + c.radius_growth_per_m * d + heading_m);
}

CandidateSet FindCandidates(const KeyframeIndex& index, const CandidateQuery& query,
                            const CandidateSearchConfig& c) {
  CandidateSet set;
  set.used_prior = c.use_pose_prior;
  std::vector<KeyframeIndex::Hit> hits;
  if (c.use_pose_prior) {
    set.radius_m = SearchRadius(c, query.travelled_since_loop_m, query.seconds_since_loop_s);
    hits = index.Within(query.position_world, set.radius_m);
  } else {
    set.radius_m = std::numeric_limits<double>::infinity();
    hits = index.All(query.position_world);
  }
  set.considered = static_cast<int>(hits.size());
  hits.erase(std::remove_if(hits.begin(), hits.end(),
                            [&](const KeyframeIndex::Hit& h) {
                              return h.path_begin_m > query.path_begin_m - c.exclude_recent_path_m;
                            }),
             hits.end());
  std::sort(hits.begin(), hits.end(), [](const KeyframeIndex::Hit& a, const KeyframeIndex::Hit& b) {
    return a.distance_m != b.distance_m ? a.distance_m < b.distance_m : a.id < b.id;
  });
  // Without a prior every keyframe is checked: capping would drop the true match.
  if (c.use_pose_prior && c.max_candidates > 0 &&
      static_cast<int>(hits.size()) > c.max_candidates) {
    hits.resize(c.max_candidates);
  }
  for (const auto& h : hits) set.ids.push_back(h.id);
  return set;
}

}  // namespace uwbsar
