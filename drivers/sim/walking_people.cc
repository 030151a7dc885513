#include "drivers/sim/walking_people.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "drivers/sim/sim_environment.h"

namespace uwbsar::sim {
namespace {

constexpr int kAttemptsPerPerson = 200;

// True when every cell within `radius_m` of the segment a-b is free.
bool FreePath(const OccupancyGrid& grid, const Point2& a, const Point2& b, double radius_m) {
  const double length = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
  const int steps = std::max(1, static_cast<int>(std::ceil(length / (0.5 * grid.resolution_m))));
  const int reach = static_cast<int>(std::ceil(radius_m / grid.resolution_m)) + 1;
  for (int k = 0; k <= steps; ++k) {
    const Point2 p{a.x_m + (b.x_m - a.x_m) * k / steps, a.y_m + (b.y_m - a.y_m) * k / steps};
    int row = 0, col = 0;
    if (!grid.CellOf(p, &row, &col)) return false;
    for (int r = row - reach; r <= row + reach; ++r) {
      for (int c = col - reach; c <= col + reach; ++c) {
        if (!grid.InBounds(r, c)) return false;
        const Point2 q = grid.CellCenter(r, c);
        if (std::hypot(q.x_m - p.x_m, q.y_m - p.y_m) <= radius_m + 0.5 * grid.resolution_m &&
            !grid.IsFree(r, c)) {
          return false;
        }
      }
    }
  }
  return true;
}

}  // namespace

SimDisc WalkingPerson::At(double t_s) const {
  const double length = std::hypot(to.x_m - from.x_m, to.y_m - from.y_m);
  SimDisc d = disc;
  if (length <= 0) return d;
  const double s = std::fmod(phase_m + speed_mps * t_s, 2.0 * length);
  const double f = (s <= length ? s : 2.0 * length - s) / length;
  d.x_m = from.x_m + f * (to.x_m - from.x_m);
  d.y_m = from.y_m + f * (to.y_m - from.y_m);
  return d;
}

std::vector<WalkingPerson> PlaceWalkingPeople(const OccupancyGrid& grid,
                                              const std::vector<Point2>& route,
                                              const SimPeopleConfig& config, std::uint64_t seed) {
  std::vector<WalkingPerson> people;
  if (config.count <= 0 || route.size() < 2) return people;
  std::mt19937_64 rng(DeriveSeed(seed, 0x9e0913));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> segment(0, route.size() - 2);
  const double radius = 0.5 * config.width_m, half = 0.5 * config.walk_length_m;
  for (int attempt = 0; attempt < kAttemptsPerPerson * config.count &&
                        static_cast<int>(people.size()) < config.count;
       ++attempt) {
    const std::size_t i = segment(rng);
    const Point2 &a = route[i], &b = route[i + 1];
    const double length = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
    const double t = unit(rng), side = unit(rng) < 0.5 ? -1.0 : 1.0;
    if (length <= 0) continue;
    const double ux = (b.x_m - a.x_m) / length, uy = (b.y_m - a.y_m) / length;
    // At most offset_m beside the route, nearer where the way is narrower (never nearer than
    // the person is wide); the path runs up to walk_length_m / 2 each way, until a wall.
    const double step = grid.resolution_m;
    Point2 centre;
    bool placed = false;
    for (double offset = config.offset_m; offset >= config.width_m - 1e-9 && !placed;
         offset -= 2.0 * step) {
      centre = {a.x_m + ux * t * length - side * uy * offset,
                a.y_m + uy * t * length + side * ux * offset};
      placed = FreePath(grid, centre, centre, radius);
    }
    if (!placed) continue;
    double reach[2] = {0.0, 0.0};
    for (int end = 0; end < 2; ++end) {
      const double sign = end == 0 ? -1.0 : 1.0;
      const auto at = [&](double r) {
        return Point2{centre.x_m + sign * ux * r, centre.y_m + sign * uy * r};
      };
      while (reach[end] + step <= half + 1e-9 &&
             FreePath(grid, at(reach[end] + step), at(reach[end] + step), radius)) {
        reach[end] += step;
      }
    }
    if (reach[0] + reach[1] < std::min(1.0, config.walk_length_m) - 1e-9) continue;
    WalkingPerson person;
    person.from = {centre.x_m - ux * reach[0], centre.y_m - uy * reach[0]};
    person.to = {centre.x_m + ux * reach[1], centre.y_m + uy * reach[1]};
    person.speed_mps = config.speed_mps;
    person.phase_m = 2.0 * config.walk_length_m * unit(rng);
    const double amplitude = std::sqrt(config.rcs_m2), phase = 2.0 * M_PI * unit(rng);
    person.disc = {person.from.x_m, person.from.y_m, radius,
                   static_cast<float>(amplitude * std::cos(phase)),
                   static_cast<float>(-amplitude * std::sin(phase))};
    people.push_back(person);
  }
  return people;
}

std::vector<SimDisc> PeopleAt(const std::vector<WalkingPerson>& people, double t_s) {
  std::vector<SimDisc> discs;
  for (const WalkingPerson& p : people) discs.push_back(p.At(t_s));
  return discs;
}

double RayDiscDistance(const Point2& origin, double angle_rad, const SimDisc& disc) {
  const double ux = std::cos(angle_rad), uy = std::sin(angle_rad);
  const double wx = disc.x_m - origin.x_m, wy = disc.y_m - origin.y_m;
  const double along = wx * ux + wy * uy;
  const double c = wx * wx + wy * wy - disc.radius_m * disc.radius_m;
  const double discriminant = along * along - c;
  if (c <= 0 || discriminant < 0 || along <= 0) return -1.0;
  return along - std::sqrt(discriminant);
}

}  // namespace uwbsar::sim
