#include "eval/compare/grid_resample.h"

#include <algorithm>

namespace uwbsar {

ResampledGrid ResampleOnto(const OccupancyGrid& source, const Pose2& T_target_source,
                           const OccupancyGrid& target) {
  ResampledGrid out;
  out.grid.rows = target.rows;
  out.grid.cols = target.cols;
  out.grid.resolution_m = target.resolution_m;
  out.grid.origin = target.origin;
  out.grid.cells.assign(target.cells.size(), OccupancyGrid::kUnknown);
  auto cell = [&](int r, int c) -> std::int8_t& {
    return out.grid.cells[static_cast<std::size_t>(r) * target.cols + c];
  };
  // (a) source cell centres, pushed into the target.
  for (int r = 0; r < source.rows; ++r) {
    for (int c = 0; c < source.cols; ++c) {
      const std::int8_t v = source.At(r, c);
      if (v == OccupancyGrid::kUnknown) continue;
      ++out.source_known_cells;
      int tr = 0, tc = 0;
      if (!target.CellOf(T_target_source * source.CellCenter(r, c), &tr, &tc)) {
        ++out.source_known_outside;
        continue;
      }
      cell(tr, tc) = std::max(cell(tr, tc), v);
    }
  }
  // (b) target cell centres, pulled from the source.
  const Pose2 T_source_target = T_target_source.Inverse();
  for (int r = 0; r < target.rows; ++r) {
    for (int c = 0; c < target.cols; ++c) {
      int sr = 0, sc = 0;
      if (source.CellOf(T_source_target * target.CellCenter(r, c), &sr, &sc)) {
        cell(r, c) = std::max(cell(r, c), source.At(sr, sc));
      }
    }
  }
  return out;
}

}  // namespace uwbsar
