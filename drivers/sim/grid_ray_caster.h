// Ray casting through an occupancy grid (Amanatides-Woo cell traversal): what a
// sensor sees. The radar lights the first occupied surface along each ray of
// its sector (plus a penetration depth); the laser measures the distance to it;
// point targets are visible when no wall stands in front of them.
#pragma once

#include <cstdint>
#include <vector>

#include "core/pose2.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::sim {

/// A cell crossed by a ray: its index (row * cols + col) and where the ray enters it.
struct RayHit {
  int cell = -1;
  double range_m = 0.0;  ///< distance from the ray's origin to where it enters the cell
};

class GridRayCaster {
 public:
  /// Keeps a reference to `grid`, which must outlive the caster.
  explicit GridRayCaster(const OccupancyGrid& grid);

  /// The first occupied cell along the ray from `origin_world` in world direction
  /// `angle_rad`, within `max_range_m`; cell = -1 when there is none (or the ray leaves the grid).
  RayHit FirstHit(const Point2& origin_world, double angle_rad, double max_range_m) const;

  /// Occupied cells lit by a sensor at `origin_world` looking along `boresight_rad`:
  /// rays every `angular_step_rad` within +-half_angle_rad, each lighting its first occupied
  /// cell and the occupied cells it enters within `penetration_m` behind it. Appends each
  /// lit cell once to `cells` (not cleared). Not thread-safe (reuses a marking buffer).
  void LitCells(const Point2& origin_world, double boresight_rad, double half_angle_rad,
                double max_range_m, double penetration_m, double angular_step_rad,
                std::vector<int>* cells);

  /// True when nothing occupied stands between `from` and `to` farther than `tolerance_m`
  /// in front of `to` (a target standing on, or just behind, a surface stays visible).
  bool Visible(const Point2& from_world, const Point2& to_world, double tolerance_m) const;

  const OccupancyGrid& grid() const { return grid_; }
  bool occupied(int cell) const { return occupied_[cell] != 0; }

 private:
  /// Calls visit(cell, entry_range_m) for every cell along the ray, in order, until it
  /// returns false, the ray leaves the grid or passes max_range_m.
  template <class Visit>
  void Traverse(const Point2& origin_world, double angle_rad, double max_range_m,
                Visit&& visit) const;

  const OccupancyGrid& grid_;
  std::vector<std::uint8_t> occupied_;  ///< per cell, row 0 = top
  std::vector<std::uint32_t> mark_;     ///< generation stamps for LitCells de-duplication
  std::uint32_t generation_ = 0;
};

}  // namespace uwbsar::sim
