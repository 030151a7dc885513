#include "drivers/sim/trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace uwbsar::sim {
namespace {

constexpr double kMaxFilletTurnRad = 120.0 * M_PI / 180.0;

/// Pose after driving `ds` along a piece of curvature `k` from `start`.
Pose2 Advance(const Pose2& start, double k, double ds) {
  if (std::abs(k) < 1e-12) return start * Pose2{ds, 0.0, 0.0};
  const double a = k * ds;
  return start * Pose2{std::sin(a) / k, (1.0 - std::cos(a)) / k, a};
}

}  // namespace

Trajectory::Profile Trajectory::Profile::Make(double distance, double max_rate, double accel) {
  Profile p;
  p.distance = distance;
  p.accel = accel;
  if (distance <= 0.0) return p;
  p.peak = std::min(max_rate, std::sqrt(distance * accel));
  p.t_accel = p.peak / accel;
  p.t_cruise = std::max(0.0, (distance - p.peak * p.t_accel) / p.peak);
  return p;
}

double Trajectory::Profile::Position(double t) const {
  if (distance <= 0.0 || t <= 0.0) return 0.0;
  const double d_accel = 0.5 * accel * t_accel * t_accel;
  if (t < t_accel) return 0.5 * accel * t * t;
  if (t < t_accel + t_cruise) return d_accel + peak * (t - t_accel);
  const double tb = std::min(t - t_accel - t_cruise, t_accel);
  return std::min(distance, d_accel + peak * t_cruise + peak * tb - 0.5 * accel * tb * tb);
}

double Trajectory::Profile::Rate(double t) const {
  if (distance <= 0.0 || t <= 0.0) return 0.0;
  if (t < t_accel) return accel * t;
  if (t < t_accel + t_cruise) return peak;
  return std::max(0.0, peak - accel * (t - t_accel - t_cruise));
}

namespace {

/// Heading and length of each leg between consecutive waypoints.
void Legs(const Route& route, std::vector<double>* heading, std::vector<double>* length) {
  const std::vector<Point2>& w = route.waypoints;
  for (std::size_t i = 0; i + 1 < w.size(); ++i) {
    heading->push_back(std::atan2(w[i + 1].y_m - w[i].y_m, w[i + 1].x_m - w[i].x_m));
    length->push_back(std::hypot(w[i + 1].x_m - w[i].x_m, w[i + 1].y_m - w[i].y_m));
    if (length->back() < 1e-6) {
      throw InputError("route '" + route.name + "': waypoints " + std::to_string(i) + " and " +
                       std::to_string(i + 1) + " coincide");
    }
  }
  if (heading->empty()) throw InputError("route '" + route.name + "' needs two waypoints");
}

/// Corner i sits at waypoint i (1 .. n-2): turn angle, and tangent length and radius
/// if rounded (0 where the robot turns on the spot).
struct Corners {
  std::vector<double> turn, tangent, radius;
};

Corners PlanCorners(const std::vector<double>& heading, const std::vector<double>& length,
                    double corner_radius_m) {
  const std::size_t n = heading.size() + 1;
  Corners c{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  for (std::size_t i = 1; i + 1 < n; ++i) {
    double phi = NormalizeAngle(heading[i] - heading[i - 1]);
    if (phi < -M_PI + 1e-9) phi = M_PI;  // reversals turn left
    c.turn[i] = phi;
    if (std::abs(phi) < 1e-9 || std::abs(phi) > kMaxFilletTurnRad || corner_radius_m <= 0) continue;
    const double half_tan = std::tan(0.5 * std::abs(phi));
    c.tangent[i] = std::min(corner_radius_m * half_tan, 0.5 * std::min(length[i - 1], length[i]));
    c.radius[i] = c.tangent[i] / half_tan;
  }
  return c;
}

}  // namespace

// Appends phases in time order: pauses, runs (lines and arcs driven under one speed
// profile, collected piece by piece until closed) and turns on the spot.
class Trajectory::Planner {
 public:
  Planner(const SimRouteConfig& config, Trajectory* traj, const Pose2& start)
      : config_(config), traj_(traj), pose_(start), piece_pose_(start) {
    run_.kind = Phase::Kind::kRun;
  }

  void AddPause() {
    Phase pause;
    pause.duration_s = config_.pause_s;
    AddPhase(pause);
  }

  /// Extends the open run by a line (curvature 0) or an arc.
  void AddPiece(double len, double curvature) {
    if (len <= 1e-9) return;
    run_.pieces.push_back({run_length_, len, curvature, piece_pose_, run_heading_});
    piece_pose_ = Advance(piece_pose_, curvature, len);
    run_length_ += len;
    run_heading_ += curvature * len;
  }

  /// A rounded corner of `radius_m` turning by `turn_rad`, within the open run.
  void AddArc(double radius_m, double turn_rad) {
    AddPiece(radius_m * std::abs(turn_rad), (turn_rad > 0 ? 1.0 : -1.0) / radius_m);
    min_radius_ = std::min(min_radius_, radius_m);
  }

  /// Closes the open run, then turns on the spot by `turn_rad`.
  void AddRotation(double turn_rad) {
    CloseRun();
    Phase rotate;
    rotate.kind = Phase::Kind::kRotate;
    rotate.rotation_rad = turn_rad;
    rotate.profile =
        Profile::Make(std::abs(turn_rad), config_.turn_rate_radps, config_.turn_accel_radps2);
    rotate.duration_s = rotate.profile.Duration();
    AddPhase(rotate);
    pose_.yaw_rad = NormalizeAngle(pose_.yaw_rad + turn_rad);
    total_heading_ += turn_rad;
    piece_pose_ = pose_;
  }

  /// The open run becomes a phase, its speed limited on its tightest arc.
  void CloseRun() {
    if (run_.pieces.empty()) return;
    const double v_max = std::min(config_.speed_mps, config_.turn_rate_radps * min_radius_);
    run_.profile = Profile::Make(run_length_, v_max, config_.accel_mps2);
    run_.duration_s = run_.profile.Duration();
    AddPhase(run_);
    pose_ = piece_pose_;
    path_ += run_length_;
    total_heading_ += run_heading_;
    run_ = Phase{};
    run_.kind = Phase::Kind::kRun;
    run_length_ = run_heading_ = 0.0;
    min_radius_ = 1e300;
  }

  void Finish() {
    traj_->duration_s_ = t_;
    traj_->length_m_ = path_;
  }

 private:
  void AddPhase(Phase phase) {
    phase.t0_s = t_;
    phase.start = pose_;
    phase.path0_m = path_;
    phase.heading0_rad = total_heading_;
    t_ += phase.duration_s;
    traj_->phases_.push_back(std::move(phase));
  }

  const SimRouteConfig& config_;
  Trajectory* traj_;
  Pose2 pose_;  ///< where the next phase starts
  double t_ = 0.0, path_ = 0.0, total_heading_ = 0.0;
  Phase run_;  ///< the open run
  double run_length_ = 0.0, run_heading_ = 0.0, min_radius_ = 1e300;
  Pose2 piece_pose_;  ///< where the open run's next piece starts
};

Trajectory Trajectory::Plan(const Route& route, const SimRouteConfig& config) {
  std::vector<double> heading, length;
  Legs(route, &heading, &length);
  const Corners corners = PlanCorners(heading, length, config.corner_radius_m);
  const std::vector<Point2>& w = route.waypoints;
  const std::size_t n = w.size();
  Trajectory traj;
  traj.name_ = route.name;
  Planner planner(config, &traj, Pose2{w[0].x_m, w[0].y_m, heading[0]});
  planner.AddPause();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    planner.AddPiece(length[i] - corners.tangent[i] - corners.tangent[i + 1], 0.0);
    const std::size_t c = i + 1;  // the corner at the segment's end
    if (c + 1 >= n || std::abs(corners.turn[c]) < 1e-9) continue;
    if (corners.radius[c] > 0.0) {
      planner.AddArc(corners.radius[c], corners.turn[c]);
    } else {
      planner.AddRotation(corners.turn[c]);
    }
  }
  planner.CloseRun();
  planner.AddPause();
  planner.Finish();
  return traj;
}

RobotState Trajectory::At(double t_s) const {
  const double t = std::clamp(t_s, 0.0, duration_s_);
  auto it = std::upper_bound(phases_.begin(), phases_.end(), t,
                             [](double v, const Phase& p) { return v < p.t0_s; });
  const Phase& phase = *(it == phases_.begin() ? it : it - 1);
  const double local = std::min(t - phase.t0_s, phase.duration_s);
  RobotState state;
  state.T_world_robot = phase.start;
  state.path_m = phase.path0_m;
  state.heading_rad = phase.heading0_rad;
  if (phase.kind == Phase::Kind::kRun) {
    const double s = phase.profile.Position(local);
    auto pit = std::upper_bound(phase.pieces.begin(), phase.pieces.end(), s,
                                [](double v, const Piece& p) { return v < p.s0_m; });
    const Piece& piece = *(pit == phase.pieces.begin() ? pit : pit - 1);
    const double ds = std::min(s - piece.s0_m, piece.length_m);
    state.T_world_robot = Advance(piece.start, piece.curvature, ds);
    state.linear_mps = phase.profile.Rate(local);
    state.angular_radps = piece.curvature * state.linear_mps;
    state.path_m += s;
    state.heading_rad += piece.heading0_rad + piece.curvature * ds;
  } else if (phase.kind == Phase::Kind::kRotate) {
    const double sign = phase.rotation_rad >= 0 ? 1.0 : -1.0;
    const double angle = sign * phase.profile.Position(local);
    state.T_world_robot.yaw_rad = NormalizeAngle(phase.start.yaw_rad + angle);
    state.angular_radps = sign * phase.profile.Rate(local);
    state.heading_rad += angle;
  }
  return state;
}

void Trajectory::CheckClearance(const OccupancyGrid& grid, double clearance_m) const {
  const double step_s = 0.005;  // 1 cm at 2 m/s
  const int reach = static_cast<int>(std::ceil(clearance_m / grid.resolution_m)) + 1;
  for (double t = 0.0; t <= duration_s_ + 1e-9; t += step_s) {
    const Pose2 pose = At(t).T_world_robot;
    double r = 0.0, c = 0.0;
    grid.WorldToCell({pose.x_m, pose.y_m}, &r, &c);
    const int r0 = static_cast<int>(std::floor(r)), c0 = static_cast<int>(std::floor(c));
    for (int row = r0 - reach; row <= r0 + reach; ++row) {
      for (int col = c0 - reach; col <= c0 + reach; ++col) {
        if (!grid.InBounds(row, col) || !grid.IsOccupied(row, col)) continue;
        // Distance from the robot's centre to the cell's square, in cell units.
        const double dx = std::max({col - c, 0.0, c - (col + 1)});
        const double dy = std::max({row - r, 0.0, r - (row + 1)});
        if (std::hypot(dx, dy) * grid.resolution_m < clearance_m) {
          const Point2 cell = grid.CellCenter(row, col);
          char msg[200];
          std::snprintf(msg, sizeof(msg),
                        "route '%s' drives the robot (x=%.2f, y=%.2f at t=%.1f s) within "
                        "%.2f m of the occupied cell at (%.2f, %.2f)",
                        name_.c_str(), pose.x_m, pose.y_m, t, clearance_m, cell.x_m, cell.y_m);
          throw InputError(msg);
        }
      }
    }
  }
}

}  // namespace uwbsar::sim
