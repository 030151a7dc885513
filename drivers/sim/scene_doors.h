// Doors of an occupancy grid, for the simulator's changed building (drivers/sim/scene_change.h).
// A map_server map holds no door objects, so doors are read from the shape of its walls, along
// rows and along columns:
//  - a doorway: a gap of free cells door_width_min_m .. door_width_max_m wide in a straight wall
//    no thicker than wall_max_thickness_m, the wall going on for kWallRunM or more on both
//    sides; closing it fills the gap across the wall's thickness;
//  - an openable wall: a straight wall no thicker than wall_max_thickness_m with free cells on
//    both sides; opening it frees OpenedDoorWidthM() of it, kWallRunM or more from its ends.
#pragma once

#include <vector>

#include "drivers/sim/simulator_config.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::sim {

/// A rectangle of cells, rows row0..row1 and columns col0..col1 (inclusive).
struct CellBox {
  int row0 = 0, row1 = -1, col0 = 0, col1 = -1;

  /// The cells' indices (row * cols + col).
  std::vector<int> Cells(int cols) const;
};

/// Wall left on each side of a doorway, or of an opened door.
constexpr double kWallRunM = 0.3;

/// Width of a door opened in a wall: the middle of the doorway widths.
inline double OpenedDoorWidthM(const SimSceneChangeConfig& config) {
  return 0.5 * (config.door_width_min_m + config.door_width_max_m);
}

/// The doorways of `grid` (each box spans the gap across the wall's thickness).
std::vector<CellBox> FindDoorways(const OccupancyGrid& grid, const SimSceneChangeConfig& config);

/// Every place a door can be opened in a thin wall of `grid` (each box: the wall cells to free).
std::vector<CellBox> FindOpenableWalls(const OccupancyGrid& grid,
                                       const SimSceneChangeConfig& config);

}  // namespace uwbsar::sim
