// Small hand-made worlds for the simulator tests.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "imaging/occupancy_grid.h"
#include "test/shared_data.h"

namespace uwbsar::sim::testing {

/// An all-free grid of rows x cols cells with its bottom-left corner at (x0, y0).
inline OccupancyGrid FreeGrid(int rows, int cols, double resolution_m, double x0_m, double y0_m) {
  OccupancyGrid g;
  g.rows = rows;
  g.cols = cols;
  g.resolution_m = resolution_m;
  g.origin = {x0_m, y0_m, 0.0};
  g.cells.assign(static_cast<std::size_t>(rows) * cols, OccupancyGrid::kFree);
  return g;
}

/// Marks the cell holding world point p occupied; returns its index.
inline int Occupy(OccupancyGrid* g, Point2 p) {
  int row = 0, col = 0;
  if (!g->CellOf(p, &row, &col)) return -1;
  const int cell = row * g->cols + col;
  g->cells[cell] = OccupancyGrid::kOccupied;
  return cell;
}

/// A wall of occupied cells along y = y_m, from x0 to x1.
inline std::vector<int> WallAlongX(OccupancyGrid* g, double y_m, double x0_m, double x1_m) {
  std::vector<int> cells;
  for (double x = x0_m; x <= x1_m; x += 0.5 * g->resolution_m) {
    const int c = Occupy(g, {x, y_m});
    if (c >= 0 && (cells.empty() || cells.back() != c)) cells.push_back(c);
  }
  return cells;
}

inline std::string SeedLabMap() { return ::uwbsar::testing::SeedLabLidarMap(); }

}  // namespace uwbsar::sim::testing
