// The robot's true motion along a route, as a function of time: a differential-
// drive base that drives straight segments and rounded corners (arcs of
// corner_radius_m) with trapezoidal speed profiles, and stops to turn on the
// spot at sharp corners (reversals), also with a trapezoidal rate profile.
// Heading is continuous everywhere; speed ramps at accel_mps2. The robot stands
// still for pause_s before it starts and after it arrives.
#pragma once

#include <string>
#include <vector>

#include "drivers/sim/route.h"
#include "drivers/sim/simulator_config.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::sim {

struct RobotState {
  Pose2 T_world_robot;
  double linear_mps = 0.0;
  double angular_radps = 0.0;
  double path_m = 0.0;       ///< distance driven since the start
  double heading_rad = 0.0;  ///< total yaw change since the start, not wrapped
};

class Trajectory {
 public:
  /// Plans the motion; throws InputError if the route cannot be driven (fewer than two
  /// distinct waypoints).
  static Trajectory Plan(const Route& route, const SimRouteConfig& config);

  double duration_s() const { return duration_s_; }
  double length_m() const { return length_m_; }
  /// The true state at time t (clamped to [0, duration]).
  RobotState At(double t_s) const;

  /// Throws InputError naming the route and the place where the robot's centre passes
  /// closer than `clearance_m` to an occupied cell of `grid`.
  void CheckClearance(const OccupancyGrid& grid, double clearance_m) const;

 private:
  class Planner;  ///< appends the phases of Plan() (trajectory.cc)

  /// A straight line (curvature 0) or an arc, within a run.
  struct Piece {
    double s0_m = 0.0;  ///< run distance at the piece's start
    double length_m = 0.0;
    double curvature = 0.0;  ///< 1/m, > 0 turns left
    Pose2 start;
    double heading0_rad = 0.0;
  };
  /// Trapezoidal profile over a distance (or angle): accelerate, cruise, brake.
  struct Profile {
    double distance = 0.0, peak = 0.0, accel = 1.0, t_accel = 0.0, t_cruise = 0.0;
    static Profile Make(double distance, double max_rate, double accel);
    double Duration() const { return 2.0 * t_accel + t_cruise; }
    double Position(double t) const;
    double Rate(double t) const;
  };
  struct Phase {
    enum class Kind { kPause, kRun, kRotate } kind = Kind::kPause;
    double t0_s = 0.0, duration_s = 0.0;
    Pose2 start;
    double path0_m = 0.0, heading0_rad = 0.0;
    std::vector<Piece> pieces;  ///< kRun
    double rotation_rad = 0.0;  ///< kRotate (signed)
    Profile profile;            ///< kRun: metres; kRotate: radians
  };

  std::string name_;
  std::vector<Phase> phases_;
  double duration_s_ = 0.0;
  double length_m_ = 0.0;
};

}  // namespace uwbsar::sim
