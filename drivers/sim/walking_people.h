// People walking past during a simulated run (simulator.people): each walks to and fro at
// speed_mps along a straight path parallel to a random stretch of the route, offset_m beside it
// (nearer, down to width_m, where the way is narrower), up to walk_length_m / 2 each way from
// there until a wall (at least 1 m in all), on free cells at least width_m / 2 from any
// occupied one. A person is
// a disc width_m across: the radars see one reflector of rcs_m2 on its side facing the antenna
// unless a wall hides it (a person hides no wall from the radars); the LiDAR measures the
// distance to the disc. Drawn from the run's seed: each run sees its own people.
#pragma once

#include <cstdint>
#include <vector>

#include "core/pose2.h"
#include "drivers/sim/simulator_config.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::sim {

/// A moving reflector at one instant: a disc in the world frame with the reflection coefficient
/// of its near side (as SimScatterer's).
struct SimDisc {
  double x_m = 0.0;
  double y_m = 0.0;
  double radius_m = 0.0;
  float in_phase = 0.0f;
  float quadrature = 0.0f;
};

struct WalkingPerson {
  Point2 from, to;         ///< the path's ends (world frame)
  double speed_mps = 1.0;  ///< walking speed
  double phase_m = 0.0;    ///< distance walked at t = 0, into the round trip from -> to -> from
  SimDisc disc;            ///< the person (its position: at `from`)

  /// The person at `t_s` seconds into the run.
  SimDisc At(double t_s) const;
};

/// config.count people beside `route` (its waypoints), drawn from `seed`; fewer where the grid
/// has no free path for one.
std::vector<WalkingPerson> PlaceWalkingPeople(const OccupancyGrid& grid,
                                              const std::vector<Point2>& route,
                                              const SimPeopleConfig& config, std::uint64_t seed);

/// Every person at `t_s`.
std::vector<SimDisc> PeopleAt(const std::vector<WalkingPerson>& people, double t_s);

/// Distance along the ray from `origin` in world direction `angle_rad` to the disc's edge;
/// negative when the ray misses it (or starts inside it).
double RayDiscDistance(const Point2& origin, double angle_rad, const SimDisc& disc);

}  // namespace uwbsar::sim
