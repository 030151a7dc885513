// The kidnapped robot (simulator.carried): carried along its route with its wheels off the
// ground, the encoders count nothing, while a Kobuki's gyro still measures the turn it is
// carried through; after the carry the odometry drives on from where it stood still.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/config_io.h"
#include "drivers/sim/base_odometry.h"
#include "drivers/sim/route.h"
#include "drivers/sim/simulator_config.h"
#include "drivers/sim/trajectory.h"

namespace uwbsar::sim {
namespace {

struct Drive {
  Pose2 at_carry_start, at_carry_end, end;  ///< the odometry there
  RobotState truth_end;
};

/// An L: 6 m east, then 6 m north (the corner at 6 m); carried over [4, 9) m of path.
Drive DriveTheL(const std::string& profile) {
  SimRouteConfig rc;
  const Trajectory t = Trajectory::Plan(Route{"L", {{0, 0}, {6, 0}, {6, 6}}}, rc);
  SimOdometryConfig c;
  c.profile = profile;
  c.wheel_scale_error = c.wheel_scale_asymmetry = c.wheelbase_error = c.wheel_slip_std = 0.0;
  c.gyro.rate_noise_density_dps_per_sqrt_hz = c.gyro.turn_on_bias_std_dps = 0.0;
  c.gyro.bias_walk_dps_per_sqrt_s = c.gyro.scale_error = c.gyro.angle_resolution_deg = 0.0;
  BaseOdometrySimulator odometry(c, t.At(0.0), 1, 2);
  Drive d;
  const int n = static_cast<int>(std::floor(t.duration_s() * c.rate_hz));
  for (int i = 0; i <= n; ++i) {
    const RobotState truth = t.At(i / c.rate_hz);
    const bool carried = truth.path_m > 4.0 && truth.path_m <= 9.0;
    const Pose2 pose = odometry.Step(SecondsToNs(i / c.rate_hz), truth, carried).T_world_robot;
    if (truth.path_m <= 4.0) d.at_carry_start = pose;
    if (truth.path_m <= 9.0) d.at_carry_end = pose;
    d.end = pose;
    d.truth_end = truth;
  }
  return d;
}

TEST(CarriedRobotTest, TheWheelsCountNothingWhileCarriedAndAGyroStillSeesTheTurn) {
  const Drive gyro = DriveTheL("kobuki_gyro");
  // Carried over the corner: the odometry stood where the carry began ...
  EXPECT_NEAR(gyro.at_carry_end.x_m, gyro.at_carry_start.x_m, 0.01);
  EXPECT_NEAR(gyro.at_carry_end.y_m, gyro.at_carry_start.y_m, 0.01);
  // ... but its heading turned with the robot (the gyro), and it drove on north, 5 m short.
  EXPECT_NEAR(NormalizeAngle(gyro.end.yaw_rad - gyro.truth_end.T_world_robot.yaw_rad), 0.0, 0.01);
  EXPECT_NEAR(gyro.end.x_m, 4.0, 0.05);
  EXPECT_NEAR(gyro.end.y_m, gyro.truth_end.T_world_robot.y_m - 3.0, 0.15);

  // Wheels alone saw no turn either: the odometry drives on east.
  const Drive wheel = DriveTheL("wheel");
  EXPECT_NEAR(wheel.at_carry_end.x_m, wheel.at_carry_start.x_m, 0.01);
  EXPECT_NEAR(std::abs(NormalizeAngle(wheel.end.yaw_rad - wheel.truth_end.T_world_robot.yaw_rad)),
              M_PI / 2, 0.01);
  EXPECT_NEAR(wheel.end.y_m, 0.0, 0.05);
  EXPECT_NEAR(wheel.end.x_m, 4.0 + wheel.truth_end.T_world_robot.y_m - 3.0, 0.15);
}

TEST(CarriedRobotTest, ACarryIsOffByDefaultAndItsKeysAreChecked) {
  SimulatorConfig c;
  EXPECT_FALSE(c.carried.at_path_m.has_value());
  c.carried.at_path_m = -1.0;
  EXPECT_THROW(Validate(c, "robot.yaml"), ConfigError);
  c.carried.at_path_m = 20.0;
  c.carried.distance_m = 0.0;
  EXPECT_THROW(Validate(c, "robot.yaml"), ConfigError);
  c.carried.distance_m = 10.0;
  EXPECT_NO_THROW(Validate(c, "robot.yaml"));
}

}  // namespace
}  // namespace uwbsar::sim
