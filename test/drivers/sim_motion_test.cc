// Routes, the planned motion and the wheel-odometry model.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "drivers/sim/route.h"
#include "drivers/sim/trajectory.h"
#include "drivers/sim/wheel_odometry.h"
#include "test/drivers/sim_test_util.h"

namespace uwbsar::sim {
namespace {

namespace fs = std::filesystem;

std::string WriteTemp(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / ("uwbsar_sim_" + name);
  std::ofstream(path) << text;
  return path.string();
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RouteTest, BuiltInRoutesStartAtTheConfiguredPose) {
  SimRouteConfig c;
  c.start_x_m = 1.0;
  c.start_yaw_deg = 90.0;
  const Route dr = BuiltInRoute("depart-return", c);
  ASSERT_EQ(dr.waypoints.size(), 3u);
  EXPECT_NEAR(dr.waypoints[1].x_m, 1.0, 1e-12);
  EXPECT_NEAR(dr.waypoints[1].y_m, 7.5, 1e-12);
  EXPECT_NEAR(dr.waypoints[2].y_m, 0.0, 1e-12);
  const Route loop = BuiltInRoute("loop", c);
  ASSERT_EQ(loop.waypoints.size(), 5u);
  EXPECT_NEAR(loop.waypoints[2].x_m, 1.0 - c.loop_width_m, 1e-12);  // turns left
  EXPECT_NEAR(loop.waypoints[4].x_m, 1.0, 1e-12);                   // closed
}

TEST(RouteTest, WaypointsFileAcceptsCommentsCommasAndRepeats) {
  const std::string path =
      WriteTemp("ok.txt", "# a zig-zag\n0 0\n\n1.5, 0.5  # second\n1.5 0.5\n3 0\n");
  const Route r = ReadWaypointsFile(path);
  ASSERT_EQ(r.waypoints.size(), 3u);
  EXPECT_DOUBLE_EQ(r.waypoints[1].y_m, 0.5);
  EXPECT_EQ(ResolveRoute(path, SimRouteConfig{}).waypoints.size(), 3u);
}

TEST(RouteTest, BadWaypointsNameFileAndLine) {
  const std::string bad = WriteTemp("bad.txt", "0 0\n1 x\n");
  EXPECT_NE(ErrorOf([&] { ReadWaypointsFile(bad); }).find("bad.txt:2"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadWaypointsFile(bad); }).find("y_m"), std::string::npos);
  const std::string three = WriteTemp("three.txt", "0 0 0\n");
  EXPECT_NE(ErrorOf([&] { ReadWaypointsFile(three); }).find("three.txt:1"), std::string::npos);
  const std::string one = WriteTemp("one.txt", "0 0\n0 0\n");
  EXPECT_NE(ErrorOf([&] { ReadWaypointsFile(one); }).find("two distinct"), std::string::npos);
  const std::string unknown = ErrorOf([] { ResolveRoute("figure-eight", SimRouteConfig{}); });
  EXPECT_NE(unknown.find("depart-return, loop"), std::string::npos) << unknown;
}

TEST(TrajectoryTest, DepartReturnGoesOutTurnsOnTheSpotAndComesBack) {
  const SimRouteConfig c;
  const Trajectory t = Trajectory::Plan(BuiltInRoute("depart-return", c), c);
  EXPECT_NEAR(t.length_m(), 15.0, 1e-9);
  const RobotState end = t.At(t.duration_s());
  EXPECT_NEAR(end.T_world_robot.x_m, 0.0, 1e-9);
  EXPECT_NEAR(end.T_world_robot.y_m, 0.0, 1e-9);
  EXPECT_NEAR(std::abs(end.T_world_robot.yaw_rad), M_PI, 1e-9);
  EXPECT_NEAR(end.heading_rad, M_PI, 1e-9);  // a left turn
  EXPECT_EQ(end.linear_mps, 0.0);
  // Farthest point 7.5 m out; the turn happens there, standing still.
  double farthest = 0.0, max_speed = 0.0, max_rate = 0.0;
  for (double s = 0.0; s <= t.duration_s(); s += 0.01) {
    const RobotState st = t.At(s);
    farthest = std::max(farthest, st.T_world_robot.x_m);
    max_speed = std::max(max_speed, st.linear_mps);
    max_rate = std::max(max_rate, std::abs(st.angular_radps));
    EXPECT_NEAR(st.T_world_robot.y_m, 0.0, 1e-9);
    if (std::abs(st.angular_radps) > 1e-9) {
      EXPECT_EQ(st.linear_mps, 0.0);
      EXPECT_NEAR(st.T_world_robot.x_m, 7.5, 1e-9);
    }
  }
  EXPECT_NEAR(farthest, 7.5, 1e-9);
  EXPECT_NEAR(max_speed, c.speed_mps, 1e-9);
  EXPECT_LE(max_rate, c.turn_rate_radps + 1e-9);
  // Standing still during the pauses at both ends.
  EXPECT_EQ(t.At(0.5 * c.pause_s).path_m, 0.0);
  EXPECT_NEAR(t.At(t.duration_s() - 0.5 * c.pause_s).path_m, 15.0, 1e-9);
}

TEST(TrajectoryTest, MotionIsContinuousWithBoundedAcceleration) {
  const SimRouteConfig c;
  const Trajectory t = Trajectory::Plan(BuiltInRoute("loop", c), c);
  const double dt = 0.005;
  RobotState prev = t.At(0.0);
  for (double s = dt; s <= t.duration_s(); s += dt) {
    const RobotState st = t.At(s);
    // Position and heading move at most as fast as the velocities allow.
    EXPECT_LE(Distance(prev.T_world_robot, st.T_world_robot), c.speed_mps * dt + 1e-9);
    EXPECT_LE(std::abs(NormalizeAngle(st.T_world_robot.yaw_rad - prev.T_world_robot.yaw_rad)),
              c.turn_rate_radps * dt + 1e-9);
    EXPECT_LE(std::abs(st.linear_mps - prev.linear_mps), c.accel_mps2 * dt + 1e-9);
    EXPECT_GE(st.path_m, prev.path_m);
    prev = st;
  }
}

TEST(TrajectoryTest, LoopCornersAreRoundedAndTheLoopCloses) {
  const SimRouteConfig c;
  const Trajectory t = Trajectory::Plan(BuiltInRoute("loop", c), c);
  const RobotState end = t.At(t.duration_s());
  EXPECT_NEAR(end.T_world_robot.x_m, 0.0, 1e-9);
  EXPECT_NEAR(end.T_world_robot.y_m, 0.0, 1e-9);
  EXPECT_NEAR(end.heading_rad, 1.5 * M_PI, 1e-9);  // three left corners
  // A rounded corner of radius r misses the corner point by r (sqrt(2) - 1).
  double closest = 1e9;
  for (double s = 0.0; s <= t.duration_s(); s += 0.01) {
    const Pose2 p = t.At(s).T_world_robot;
    closest = std::min(closest, std::hypot(p.x_m - c.loop_length_m, p.y_m));
  }
  EXPECT_NEAR(closest, c.corner_radius_m * (std::sqrt(2.0) - 1.0), 0.01);
  // Path length: the rectangle less what the three rounded corners cut.
  const double cut = 3 * (2.0 * c.corner_radius_m - 0.5 * M_PI * c.corner_radius_m);
  EXPECT_NEAR(t.length_m(), 2 * (c.loop_length_m + c.loop_width_m) - cut, 1e-6);
}

TEST(TrajectoryTest, RouteThroughAWallIsAnError) {
  OccupancyGrid g = testing::FreeGrid(100, 100, 0.05, -1.0, -2.5);
  testing::WallAlongX(&g, 2.0, -1.0, 4.0);  // does not cross y = 0
  SimRouteConfig c;
  c.depart_distance_m = 3.0;
  const Trajectory ok = Trajectory::Plan(BuiltInRoute("depart-return", c), c);
  EXPECT_NO_THROW(ok.CheckClearance(g, 0.15));
  for (double y = -2.0; y < 2.0; y += 0.02) testing::Occupy(&g, {2.0, y});  // across the route
  const std::string msg = ErrorOf([&] { ok.CheckClearance(g, 0.15); });
  EXPECT_NE(msg.find("depart-return"), std::string::npos) << msg;
  EXPECT_NE(msg.find("occupied cell"), std::string::npos) << msg;
}

/// Runs the odometry model along `t` at `rate_hz`; returns (odometry, truth) at the end.
std::pair<Pose2, Pose2> DriveOdometry(const Trajectory& t, const SimOdometryConfig& c,
                                      std::uint64_t seed) {
  WheelOdometrySimulator odom(c, t.At(0.0), seed);
  OdometrySample last;
  const int n = static_cast<int>(std::floor(t.duration_s() * c.rate_hz));
  for (int i = 0; i <= n; ++i) {
    last = odom.Step(SecondsToNs(i / c.rate_hz), t.At(i / c.rate_hz));
  }
  return {last.T_world_robot, t.At(n / c.rate_hz).T_world_robot};
}

SimOdometryConfig PerfectOdometry() {
  SimOdometryConfig c;
  c.wheel_scale_error = c.wheel_scale_asymmetry = c.wheelbase_error = c.wheel_slip_std = 0.0;
  return c;
}

TEST(WheelOdometryTest, PerfectEncodersFollowTheTruth) {
  const SimRouteConfig rc;
  const Trajectory t = Trajectory::Plan(BuiltInRoute("loop", rc), rc);
  const auto [odom, truth] = DriveOdometry(t, PerfectOdometry(), 1);
  EXPECT_LT(Distance(odom, truth), 0.005);  // tick quantisation only
  EXPECT_LT(std::abs(NormalizeAngle(odom.yaw_rad - truth.yaw_rad)), 0.005);
}

TEST(WheelOdometryTest, ScaleErrorStretchesDistance) {
  SimRouteConfig rc;
  rc.depart_distance_m = 10.0;
  const Route straight{"straight", {{0, 0}, {10, 0}}};
  SimOdometryConfig c = PerfectOdometry();
  c.wheel_scale_error = 0.02;
  const auto [odom, truth] = DriveOdometry(Trajectory::Plan(straight, rc), c, 1);
  EXPECT_NEAR(odom.x_m - truth.x_m, 0.2, 0.002);
  EXPECT_NEAR(odom.y_m, 0.0, 1e-3);
}

TEST(WheelOdometryTest, WheelbaseErrorUnderReportsTurns) {
  const SimRouteConfig rc;
  SimOdometryConfig c = PerfectOdometry();
  c.wheelbase_error = 0.02;
  const Trajectory t = Trajectory::Plan(BuiltInRoute("depart-return", rc), rc);
  const auto [odom, truth] = DriveOdometry(t, c, 1);
  // The 180 deg turn is reported as 180 * (1 - 0.02) deg.
  EXPECT_NEAR(NormalizeAngle(odom.yaw_rad - truth.yaw_rad), -0.02 * M_PI, 0.003);
}

TEST(WheelOdometryTest, DefaultModelDriftsLikeARealBase) {
  // The target: about 1-2 % of distance and a few degrees per 10 m.
  SimRouteConfig rc;
  const Trajectory t = Trajectory::Plan(Route{"straight", {{0, 0}, {10, 0}}}, rc);
  double sum_pos = 0.0, sum_yaw = 0.0;
  const int runs = 10;
  for (int seed = 1; seed <= runs; ++seed) {
    const auto [odom, truth] = DriveOdometry(t, SimOdometryConfig{}, seed);
    sum_pos += Distance(odom, truth);
    sum_yaw += std::abs(NormalizeAngle(odom.yaw_rad - truth.yaw_rad));
  }
  const double pos_percent = 100.0 * sum_pos / runs / 10.0;
  const double yaw_deg = sum_yaw / runs * 180.0 / M_PI;
  EXPECT_GE(pos_percent, 1.0);
  EXPECT_LE(pos_percent, 2.5);
  EXPECT_GE(yaw_deg, 1.5);
  EXPECT_LE(yaw_deg, 6.0);
  std::printf(
      "default odometry drift over 10 m straight (mean of %d seeds): %.2f %% of "
      "distance, %.2f deg\n",
      runs, pos_percent, yaw_deg);
}

TEST(WheelOdometryTest, SameSeedSameOdometry) {
  const SimRouteConfig rc;
  const Trajectory t = Trajectory::Plan(BuiltInRoute("loop", rc), rc);
  const auto a = DriveOdometry(t, SimOdometryConfig{}, 4);
  const auto b = DriveOdometry(t, SimOdometryConfig{}, 4);
  const auto c = DriveOdometry(t, SimOdometryConfig{}, 5);
  EXPECT_EQ(a.first.x_m, b.first.x_m);
  EXPECT_EQ(a.first.yaw_rad, b.first.yaw_rad);
  EXPECT_NE(a.first.x_m, c.first.x_m);
}

}  // namespace
}  // namespace uwbsar::sim
