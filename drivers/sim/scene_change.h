// A changed building for a later run of one map ("day 2"): the map file stays the day-1
// building, and the simulator draws, from a change seed, edits of its occupancy grid:
//  - objects added: squares of object_size_min_m .. object_size_max_m, their centre
//    distance_min_m .. distance_max_m beside the route, on free cells that touch nothing;
//  - objects removed or moved: the map's own small objects (isolated blobs of occupied cells at
//    most object_max_extent_m across) within reach_m of the route; a moved one goes
//    move_min_m .. move_max_m away, at least distance_min_m from the route;
//  - doors closed (a doorway of the map filled, never within distance_min_m of the route) or
//    opened (a door-wide stretch of a thin wall freed) within reach_m of the route
//    (drivers/sim/scene_doors.h).
// No cell is edited twice. The radars and the LiDAR see the changed grid alike; the cells no
// edit touches keep their day-1 scatterers (drivers/sim/sim_environment.h). Fewer edits than
// asked are made where the map offers fewer places.
#pragma once

#include <cstdint>
#include <vector>

#include "core/pose2.h"
#include "drivers/sim/simulator_config.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::sim {

/// One edit of the building: the cells (row * cols + col) it made occupied and free.
struct SceneEdit {
  enum class Kind { kObjectAdded, kObjectRemoved, kObjectMoved, kDoorClosed, kDoorOpened };
  Kind kind = Kind::kObjectAdded;
  Point2 where;               ///< centre of the object (where it went, when moved) or door
  std::vector<int> occupied;  ///< cells turned occupied
  std::vector<int> freed;     ///< cells turned free
};

struct SceneChange {
  OccupancyGrid grid;  ///< the changed building
  std::vector<SceneEdit> edits;

  int Count(SceneEdit::Kind kind) const;
};

/// Distance (m) from every cell's centre to the polyline `path`, at most `cap_m`.
std::vector<float> DistanceToPath(const OccupancyGrid& grid, const std::vector<Point2>& path,
                                  double cap_m);

/// The building of `grid` changed by `config`'s edits, drawn from `seed` beside `route` (the
/// route's waypoints, world frame). The same grid, route, configuration and seed give the same
/// change.
SceneChange DrawSceneChange(const OccupancyGrid& grid, const std::vector<Point2>& route,
                            const SimSceneChangeConfig& config, std::uint64_t seed);

}  // namespace uwbsar::sim
