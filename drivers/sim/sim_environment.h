// The simulated world the radars look at: an occupancy grid whose occupied cells
// carry random scatterers (speckle), plus point targets such as metal poles.
// Everything random is drawn once, from the seed, when the environment is built,
// so a cell looks the same in every scan and in every run with the same seed.
#pragma once

#include <cstdint>
#include <vector>

#include "drivers/sim/simulator_config.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::sim {

/// One point scatterer with a complex reflection coefficient: its echo is
/// in_phase * p(t) + quadrature * q(t), where p is the transmitted pulse and q its
/// 90-degree-shifted twin (a reflection with amplitude A and phase phi has
/// in_phase = A cos(phi), quadrature = -A sin(phi)). Amplitude = sqrt(RCS).
struct SimScatterer {
  double x_m = 0.0;  ///< world frame
  double y_m = 0.0;
  float in_phase = 0.0f;
  float quadrature = 0.0f;
};

class SimEnvironment {
 public:
  /// Draws `radar.scatterers_per_cell` scatterers in every occupied cell: uniform
  /// positions inside the cell, uniform phases, and a cell RCS drawn from an
  /// exponential distribution of mean `radar.cell_rcs_m2` (Swerling I), shared
  /// among the cell's scatterers. Point targets get their RCS with phase pi (metal).
  /// With `changed` (a grid of the same size: a later day's building, drivers/sim/scene_change.h)
  /// the environment is that building: cells occupied in both keep the scatterers drawn for
  /// `grid`, cells only `changed` occupies draw theirs from the seed and the cell alone, so a
  /// change alters the echoes of the cells it edits and of no other.
  SimEnvironment(OccupancyGrid grid, const SimRadarConfig& radar, std::uint64_t seed,
                 const OccupancyGrid* changed = nullptr);

  const OccupancyGrid& grid() const { return grid_; }
  /// Scatterers of cell `cell` (row * cols + col): [begin, end) into scatterers().
  int CellBegin(int cell) const { return cell_begin_[cell]; }
  int CellEnd(int cell) const { return cell_begin_[cell + 1]; }
  const std::vector<SimScatterer>& scatterers() const { return scatterers_; }
  const std::vector<SimScatterer>& point_targets() const { return point_targets_; }
  int num_occupied_cells() const { return num_occupied_; }

 private:
  /// Appends the scatterers of occupied cell (row, col), drawn from `rng`.
  template <class Rng>
  void DrawCell(int row, int col, const SimRadarConfig& radar, Rng& rng);

  OccupancyGrid grid_;
  std::vector<int> cell_begin_;  ///< size cells + 1
  std::vector<SimScatterer> scatterers_;
  std::vector<SimScatterer> point_targets_;
  int num_occupied_ = 0;
};

/// A 64-bit seed for stream `a`, item `b` derived from `seed` (SplitMix64 mixing), so
/// every scan draws its own reproducible noise whatever order scans are made in.
std::uint64_t DeriveSeed(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0);

}  // namespace uwbsar::sim
