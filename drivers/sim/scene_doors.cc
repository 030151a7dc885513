#include "drivers/sim/scene_doors.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace uwbsar::sim {
namespace {

// The grid seen along rows (a wall along a row: its thickness across lines = rows) or, with
// `transposed`, along columns; line i, position j.
struct View {
  const OccupancyGrid& grid;
  bool transposed;

  int lines() const { return transposed ? grid.cols : grid.rows; }
  int along() const { return transposed ? grid.rows : grid.cols; }
  bool occupied(int i, int j) const {
    return transposed ? grid.IsOccupied(j, i) : grid.IsOccupied(i, j);
  }
  bool free(int i, int j) const { return transposed ? grid.IsFree(j, i) : grid.IsFree(i, j); }
  CellBox Box(int i0, int i1, int j0, int j1) const {
    return transposed ? CellBox{j0, j1, i0, i1} : CellBox{i0, i1, j0, j1};
  }
};

int Cells(double metres, double resolution_m) {
  return static_cast<int>(std::floor(metres / resolution_m + 1e-9));
}

// Runs (j0, j1, i) sorted so that equal spans on neighbouring lines follow each other, grouped
// into boxes at most `max_lines` thick.
template <class Emit>
void GroupRuns(std::vector<std::array<int, 3>> runs, int max_lines, Emit&& emit) {
  std::sort(runs.begin(), runs.end());
  for (std::size_t a = 0; a < runs.size();) {
    std::size_t b = a + 1;
    while (b < runs.size() && runs[b][0] == runs[a][0] && runs[b][1] == runs[a][1] &&
           runs[b][2] == runs[b - 1][2] + 1) {
      ++b;
    }
    const int thickness = runs[b - 1][2] - runs[a][2] + 1;
    if (thickness <= max_lines) emit(runs[a][2], runs[b - 1][2], runs[a][0], runs[a][1]);
    a = b;
  }
}

void Doorways(const View& v, const SimSceneChangeConfig& c, std::vector<CellBox>* out) {
  const double res = v.grid.resolution_m;
  const int wall = std::max(1, Cells(kWallRunM, res));
  const int min_w = std::max(1, static_cast<int>(std::ceil(c.door_width_min_m / res - 1e-9)));
  const int max_w = Cells(c.door_width_max_m, res);
  std::vector<std::array<int, 3>> runs;  // gap (j0, j1) on line i
  for (int i = 0; i < v.lines(); ++i) {
    int j = 0;
    while (j < v.along() && !v.occupied(i, j)) ++j;
    while (j < v.along()) {
      int k = j;
      while (k < v.along() && v.occupied(i, k)) ++k;  // [j, k) wall
      int m = k;
      while (m < v.along() && !v.occupied(i, m)) ++m;  // [k, m) gap
      if (m >= v.along()) break;
      bool ok = m - k >= min_w && m - k <= max_w && k - wall >= 0 && m + wall <= v.along();
      for (int t = k; ok && t < m; ++t) ok = v.free(i, t);
      for (int t = 1; ok && t <= wall; ++t) ok = v.occupied(i, k - t) && v.occupied(i, m - 1 + t);
      if (ok) runs.push_back({k, m - 1, i});
      j = m;
    }
  }
  GroupRuns(std::move(runs), Cells(c.wall_max_thickness_m, res),
            [&](int i0, int i1, int j0, int j1) { out->push_back(v.Box(i0, i1, j0, j1)); });
}

void OpenableWalls(const View& v, const SimSceneChangeConfig& c, std::vector<CellBox>* out) {
  const double res = v.grid.resolution_m;
  const int wall = std::max(1, Cells(kWallRunM, res));
  const int door = std::max(1, static_cast<int>(std::lround(OpenedDoorWidthM(c) / res)));
  std::vector<std::array<int, 3>> runs;  // wall across lines (i0, i1) at position j
  for (int j = 0; j < v.along(); ++j) {
    for (int i = 1; i + 1 < v.lines(); ++i) {
      if (!v.occupied(i, j) || !v.free(i - 1, j)) continue;
      int k = i;
      while (k < v.lines() && v.occupied(k, j)) ++k;
      if (k < v.lines() && v.free(k, j)) runs.push_back({i, k - 1, j});
      i = k;
    }
  }
  // The same grouping with the roles swapped: equal spans across lines at neighbouring positions.
  GroupRuns(std::move(runs), v.along(), [&](int j0, int j1, int i0, int i1) {
    if (i1 - i0 + 1 > Cells(c.wall_max_thickness_m, res)) return;
    for (int s = j0 + wall; s + door - 1 <= j1 - wall; ++s) {
      out->push_back(v.Box(i0, i1, s, s + door - 1));
    }
  });
}

}  // namespace

std::vector<int> CellBox::Cells(int cols) const {
  std::vector<int> cells;
  for (int r = row0; r <= row1; ++r) {
    for (int c = col0; c <= col1; ++c) cells.push_back(r * cols + c);
  }
  return cells;
}

std::vector<CellBox> FindDoorways(const OccupancyGrid& grid, const SimSceneChangeConfig& config) {
  std::vector<CellBox> boxes;
  Doorways({grid, false}, config, &boxes);
  Doorways({grid, true}, config, &boxes);
  return boxes;
}

std::vector<CellBox> FindOpenableWalls(const OccupancyGrid& grid,
                                       const SimSceneChangeConfig& config) {
  std::vector<CellBox> boxes;
  OpenableWalls({grid, false}, config, &boxes);
  OpenableWalls({grid, true}, config, &boxes);
  return boxes;
}

}  // namespace uwbsar::sim
