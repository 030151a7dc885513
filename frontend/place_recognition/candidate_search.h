// Which past keyframes a new keyframe is matched against. Keyframe positions live
// in a spatial hash (square cells), so a query touches only the cells within its
// radius and its cost does not grow with the length of the run. With a pose prior,
// the radius grows with the odometry travelled since the last accepted loop (drift
// grows with it); without one (re-localisation after large drift), every keyframe
// is a candidate. Keyframes that began less than exclude_recent_path_m of path
// before the query share scans with it and are never candidates.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/pose2.h"
#include "frontend/place_recognition/place_recognition_config.h"

namespace uwbsar {

class KeyframeIndex {
 public:
  explicit KeyframeIndex(double cell_m);

  /// Adds or moves keyframe `id` (e.g. after the pose graph corrected it).
  void Upsert(int id, const Point2& position_world, double path_begin_m);
  /// Forgets keyframe `id` (a retired keyframe); nothing happens for an unknown id.
  void Remove(int id);
  bool Contains(int id) const { return entries_.count(id) > 0; }
  std::size_t size() const { return entries_.size(); }

  struct Hit {
    int id = 0;
    double distance_m = 0.0;
    double path_begin_m = 0.0;
  };
  /// Keyframes within `radius_m` of `p` (unsorted); visits only the overlapping cells.
  std::vector<Hit> Within(const Point2& p, double radius_m) const;
  /// Every keyframe with its distance to `p` (unsorted).
  std::vector<Hit> All(const Point2& p) const;

 private:
  using CellKey = std::int64_t;
  CellKey KeyOf(long long cx, long long cy) const;
  long long CellOf(double v) const;

  struct Entry {
    Point2 position;
    double path_begin_m = 0.0;
    CellKey cell = 0;
  };
  double cell_m_;
  std::unordered_map<int, Entry> entries_;
  std::unordered_map<CellKey, std::vector<int>> cells_;
};

struct CandidateQuery {
  Point2 position_world;                ///< estimated position of the new keyframe
  double path_begin_m = 0.0;            ///< its odometry path at its start
  double travelled_since_loop_m = 0.0;  ///< odometry since the last accepted loop
  double seconds_since_loop_s = 0.0;    ///< time since the last accepted loop
};

struct CandidateSet {
  std::vector<int> ids;   ///< nearest first
  double radius_m = 0.0;  ///< search radius used (infinite without a prior)
  bool used_prior = true;
  int considered = 0;  ///< keyframes the index returned before filtering
};

/// Search radius for a query: base + growth * travelled, plus, for a heading whose error grows
/// with time (a gyro's bias, sigma heading_rate_sigma_radps), three sigmas of the sideways error
/// it makes over the stretch since the last loop (a heading error growing linearly in time over
/// d metres and t seconds moves the end sideways by rate * d * t / 2); capped at max_radius_m.
double SearchRadius(const CandidateSearchConfig& config, double travelled_since_loop_m,
                    double seconds_since_loop_s = 0.0);

CandidateSet FindCandidates(const KeyframeIndex& index, const CandidateQuery& query,
                            const CandidateSearchConfig& config);

}  // namespace uwbsar
