#include "drivers/sim/grid_ray_caster.h"

#include <cmath>
#include <limits>

namespace uwbsar::sim {

GridRayCaster::GridRayCaster(const OccupancyGrid& grid)
    : grid_(grid), occupied_(grid.cells.size()), mark_(grid.cells.size(), 0) {
  for (std::size_t i = 0; i < grid.cells.size(); ++i) {
    occupied_[i] = grid.cells[i] >= OccupancyGrid::kOccupiedMinValue;
  }
}

template <class Visit>
void GridRayCaster::Traverse(const Point2& origin_world, double angle_rad, double max_range_m,
                             Visit&& visit) const {
  // Work in map-frame cell units: u along columns, v upwards (v = rows - row).
  const Point2 o = grid_.origin.Inverse() * origin_world;
  const double res = grid_.resolution_m;
  const double dir_angle = angle_rad - grid_.origin.yaw_rad;
  const double du = std::cos(dir_angle), dv = std::sin(dir_angle);
  double u = o.x_m / res, v = o.y_m / res;
  const double max_t = max_range_m / res;
  double t = 0.0;
  // Enter the grid if the origin lies outside it (clip the ray to the grid's box).
  if (u < 0 || v < 0 || u >= grid_.cols || v >= grid_.rows) {
    double t0 = 0.0, t1 = max_t;
    const double lo[2] = {0.0, 0.0}, hi[2] = {double(grid_.cols), double(grid_.rows)};
    const double p[2] = {u, v}, d[2] = {du, dv};
    for (int k = 0; k < 2; ++k) {
      if (std::abs(d[k]) < 1e-15) {
        if (p[k] < lo[k] || p[k] >= hi[k]) return;
        continue;
      }
      double a = (lo[k] - p[k]) / d[k], b = (hi[k] - p[k]) / d[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    if (t0 >= t1) return;
    t = t0 + 1e-9;
    u += du * t;
    v += dv * t;
  }
  int cu = std::min(grid_.cols - 1, std::max(0, static_cast<int>(std::floor(u))));
  int cv = std::min(grid_.rows - 1, std::max(0, static_cast<int>(std::floor(v))));
  const int step_u = du > 0 ? 1 : -1, step_v = dv > 0 ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double delta_u = du != 0 ? std::abs(1.0 / du) : kInf;
  const double delta_v = dv != 0 ? std::abs(1.0 / dv) : kInf;
  double next_u = du != 0 ? t + ((du > 0 ? cu + 1 - u : u - cu) * delta_u) : kInf;
  double next_v = dv != 0 ? t + ((dv > 0 ? cv + 1 - v : v - cv) * delta_v) : kInf;
  double entry = t;
  while (entry <= max_t) {
    const int cell = (grid_.rows - 1 - cv) * grid_.cols + cu;
    if (!visit(cell, entry * res)) return;
    if (next_u < next_v) {
      entry = next_u;
      next_u += delta_u;
      cu += step_u;
      if (cu < 0 || cu >= grid_.cols) return;
    } else {
      entry = next_v;
      next_v += delta_v;
      cv += step_v;
      if (cv < 0 || cv >= grid_.rows) return;
    }
  }
}

RayHit GridRayCaster::FirstHit(const Point2& origin_world, double angle_rad,
                               double max_range_m) const {
  RayHit hit;
  Traverse(origin_world, angle_rad, max_range_m, [&](int cell, double range_m) {
    if (!occupied_[cell]) return true;
    hit = {cell, range_m};
    return false;
  });
  return hit;
}

void GridRayCaster::LitCells(const Point2& origin_world, double boresight_rad,
                             double half_angle_rad, double max_range_m, double penetration_m,
                             double angular_step_rad, std::vector<int>* cells) {
  if (++generation_ == 0) {  // wrapped: forget every old mark
    std::fill(mark_.begin(), mark_.end(), 0);
    generation_ = 1;
  }
  const int num_rays =
      std::max(1, static_cast<int>(std::ceil(2.0 * half_angle_rad / angular_step_rad))) + 1;
  const double step = num_rays > 1 ? 2.0 * half_angle_rad / (num_rays - 1) : 0.0;
  for (int i = 0; i < num_rays; ++i) {
    const double angle = boresight_rad - half_angle_rad + i * step;
    double first = -1.0;
    Traverse(origin_world, angle, max_range_m, [&](int cell, double range_m) {
      if (first >= 0.0 && range_m > first + penetration_m) return false;
      if (!occupied_[cell]) return true;
      if (first < 0.0) first = range_m;
      if (mark_[cell] != generation_) {
        mark_[cell] = generation_;
        cells->push_back(cell);
      }
      return true;
    });
  }
}

bool GridRayCaster::Visible(const Point2& from_world, const Point2& to_world,
                            double tolerance_m) const {
  const double dist = std::hypot(to_world.x_m - from_world.x_m, to_world.y_m - from_world.y_m);
  const double angle = std::atan2(to_world.y_m - from_world.y_m, to_world.x_m - from_world.x_m);
  const RayHit hit = FirstHit(from_world, angle, std::max(0.0, dist - tolerance_m));
  return hit.cell < 0;
}

}  // namespace uwbsar::sim
