#include "drivers/sim/sim_environment.h"

#include <cmath>
#include <random>
#include <stdexcept>

namespace uwbsar::sim {

std::uint64_t DeriveSeed(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  auto mix = [](std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  return mix(mix(mix(seed) ^ a) ^ b);
}

template <class Rng>
void SimEnvironment::DrawCell(int row, int col, const SimRadarConfig& radar, Rng& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::exponential_distribution<double> rcs(radar.cell_rcs_m2 > 0 ? 1.0 / radar.cell_rcs_m2 : 1.0);
  const int per_cell = radar.scatterers_per_cell;
  const double res = grid_.resolution_m;
  const double cell_rcs = radar.cell_rcs_m2 > 0 ? rcs(rng) : 0.0;
  const double amplitude = std::sqrt(cell_rcs / per_cell);
  for (int k = 0; k < per_cell; ++k) {
    // Position inside the cell, in the map frame, then to the world.
    const Point2 p =
        grid_.origin * Point2{(col + unit(rng)) * res, (grid_.rows - row - unit(rng)) * res};
    const double phase = 2.0 * M_PI * unit(rng);
    scatterers_.push_back({p.x_m, p.y_m, static_cast<float>(amplitude * std::cos(phase)),
                           static_cast<float>(-amplitude * std::sin(phase))});
  }
}

SimEnvironment::SimEnvironment(OccupancyGrid grid, const SimRadarConfig& radar, std::uint64_t seed,
                               const OccupancyGrid* changed)
    : grid_(changed != nullptr ? *changed : std::move(grid)) {
  const OccupancyGrid& day1 = changed != nullptr ? grid : grid_;
  if (day1.rows != grid_.rows || day1.cols != grid_.cols) {
    throw std::invalid_argument("SimEnvironment: the changed building has another grid size");
  }
  std::mt19937_64 rng(DeriveSeed(seed, 0x5ca77e7));
  cell_begin_.assign(grid_.cells.size() + 1, 0);
  for (int row = 0; row < grid_.rows; ++row) {
    for (int col = 0; col < grid_.cols; ++col) {
      const int cell = row * grid_.cols + col;
      cell_begin_[cell] = static_cast<int>(scatterers_.size());
      const bool was = day1.IsOccupied(row, col), is = grid_.IsOccupied(row, col);
      if (was) {
        // Drawn even when the change freed the cell, so that every other cell draws as on day 1.
        DrawCell(row, col, radar, rng);
        if (!is) scatterers_.resize(static_cast<std::size_t>(cell_begin_[cell]));
      } else if (is) {
        std::mt19937_64 cell_rng(DeriveSeed(seed, 0xadded, static_cast<std::uint64_t>(cell)));
        DrawCell(row, col, radar, cell_rng);
      }
      num_occupied_ += is;
    }
  }
  cell_begin_.back() = static_cast<int>(scatterers_.size());
  for (const PointTargetConfig& t : radar.point_targets) {
    // A conducting target reflects with phase pi.
    point_targets_.push_back({t.x_m, t.y_m, static_cast<float>(-std::sqrt(t.rcs_m2)), 0.0f});
  }
}

}  // namespace uwbsar::sim
