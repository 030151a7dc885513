#include "imaging/sector_spans.h"

#include <algorithm>
#include <cmath>

namespace uwbsar {
namespace {

/// Restricts [lo, hi] to the dx satisfying a * dx + b >= 0.
void ClipHalfLine(double a, double b, double* lo, double* hi) {
  constexpr double kEps = 1e-12;
  if (a > kEps) {
    *lo = std::max(*lo, -b / a);
  } else if (a < -kEps) {
    *hi = std::min(*hi, -b / a);
  } else if (b < 0.0) {
    *hi = *lo - 1.0;  // empty
  }
}

}  // namespace

long long ComputeSectorSpans(const ImageGrid& grid, const Pose2& T_grid_sensor,
                             const SectorShape& sector, std::vector<RowSpan>* spans) {
  const double sx = T_grid_sensor.x_m, sy = T_grid_sensor.y_m;
  const double rmax2 = sector.max_range_m * sector.max_range_m;
  const double rmin2 = sector.min_range_m * sector.min_range_m;
  // Boundary rays u_left (yaw + half) and u_right (yaw - half): inside means
  // cross(u_right, d) >= 0 and cross(u_left, d) <= 0, with d = pixel - sensor.
  const double left = T_grid_sensor.yaw_rad + sector.fov_half_angle_rad;
  const double right = T_grid_sensor.yaw_rad - sector.fov_half_angle_rad;
  const double ulx = std::cos(left), uly = std::sin(left);
  const double urx = std::cos(right), ury = std::sin(right);

  const int row_first =
      std::max(0, static_cast<int>(std::floor(grid.YToRow(sy + sector.max_range_m))));
  const int row_last =
      std::min(grid.rows - 1, static_cast<int>(std::ceil(grid.YToRow(sy - sector.max_range_m))));
  long long pixels = 0;
  auto emit = [&](int row, double x_lo, double x_hi) {
    if (x_hi < x_lo) return;
    const int c0 = std::max(0, static_cast<int>(std::ceil(grid.XToCol(x_lo))));
    const int c1 = std::min(grid.cols - 1, static_cast<int>(std::floor(grid.XToCol(x_hi))));
    if (c1 < c0) return;
    spans->push_back({row, c0, c1 + 1});
    pixels += c1 + 1 - c0;
  };
  for (int row = row_first; row <= row_last; ++row) {
    const double dy = grid.RowToY(row) - sy;
    const double dy2 = dy * dy;
    if (dy2 > rmax2) continue;
    const double outer = std::sqrt(rmax2 - dy2);
    double lo = -outer, hi = outer;
    // cross(u_right, d) = urx*dy - ury*dx >= 0  ->  (-ury) dx + urx dy >= 0
    ClipHalfLine(-ury, urx * dy, &lo, &hi);
    // -cross(u_left, d) = uly*dx - ulx*dy >= 0
    ClipHalfLine(uly, -ulx * dy, &lo, &hi);
    if (hi < lo) continue;
    if (dy2 < rmin2) {
      const double inner = std::sqrt(rmin2 - dy2);
      emit(row, sx + lo, sx + std::min(hi, -inner));
      emit(row, sx + std::max(lo, inner), sx + hi);
    } else {
      emit(row, sx + lo, sx + hi);
    }
  }
  return pixels;
}

cv::Rect SpansBounds(const std::vector<RowSpan>& spans) {
  if (spans.empty()) return cv::Rect();
  int c0 = spans.front().col_begin, c1 = spans.front().col_end;
  for (const RowSpan& s : spans) {
    c0 = std::min(c0, s.col_begin);
    c1 = std::max(c1, s.col_end);
  }
  return cv::Rect(c0, spans.front().row, c1 - c0, spans.back().row + 1 - spans.front().row);
}

}  // namespace uwbsar
