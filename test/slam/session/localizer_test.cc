// Localisation in a saved map (point 3) on short simulated seed_lab runs: a run
// starting 2 m along and 20 deg turned (another seed) is placed within 3 m, its fixes are
// all true, ATE while tracking within 5 cm, nothing added to the map; a run through a part
// of the room the map never saw stays "lost" with no fix.
#include "slam/localization/localizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "slam/app_config.h"
#include "slam/localization/localize_job.h"
#include "slam/map_job.h"
#include "slam/outputs/session_capture.h"
#include "slam/scene_simulation.h"
#include "test/shared_data.h"
#include "test/slam/session/session_test_util.h"

namespace uwbsar {
namespace {

using ::uwbsar::testing::NearestGroundTruth;
using ::uwbsar::testing::ShortSessionConfig;

TEST(LocalizerTest, TurnedRunIsPlacedWithinThreeMetresWithTrueFixesOnly) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const Config config = ShortSessionConfig();
  const Config config_b = ::uwbsar::testing::TurnedRevisitConfig(config);
  const std::string lidar = ::uwbsar::testing::SeedLabLidarMap();
  const slam::MapRun a = slam::MapSimulation(config, lidar, "depart-return", 1);
  const SessionData map = slam::CaptureSession(a);
  const slam::LocalizeRun run = slam::LocalizeSimulation(map, config_b, lidar, "depart-return", 1,
                                                         2, slam::RouteStart(config_b).Inverse());
  ASSERT_GE(run.first_fix, 0);
  EXPECT_LE(run.first_fix_path_m, 3.0);

  // The map frame in the world: its fixed first keyframe sits at its odometry pose.
  const SessionKeyframe& k0 = map.keyframes.front();
  const Pose2 T_world_k0 = NearestGroundTruth(a.ground_truth, k0.stamp_ns).T_world_robot *
                           (k0.T_odom_robot.Inverse() * k0.T_odom_anchor);
  const Pose2 T_world_map = T_world_k0 * k0.T_map_anchor.Inverse();
  int false_fixes = 0, fixes = 0;
  for (const LocalizedKeyframe& k : run.keyframes) {
    if (k.status == LocalizeStatus::kLost || k.loops == 0) continue;
    ++fixes;
    // The keyframe's true anchor: its odometry anchor rigid to the robot at its stamp.
    const Pose2 T_odom_robot = [&] {
      const OdometryEntry* best = &run.odometry.front();
      for (const OdometryEntry& e : run.odometry)
        if (std::llabs(e.stamp_ns - k.stamp_ns) < std::llabs(best->stamp_ns - k.stamp_ns))
          best = &e;
      return best->T_world_robot;
    }();
    const Pose2 truth = NearestGroundTruth(run.ground_truth, k.stamp_ns).T_world_robot *
                        (T_odom_robot.Inverse() * k.T_odom_anchor);
    const Pose2 err = Between(truth, T_world_map * k.T_map_anchor);
    false_fixes += std::hypot(err.x_m, err.y_m) > 0.2 || std::abs(err.yaw_rad) > 5.0 * M_PI / 180.0;
  }
  EXPECT_GE(fixes, 2);
  EXPECT_EQ(false_fixes, 0);
  const AteResult ate = slam::TrajectoryError(run.Trajectory(true), run.ground_truth);
  EXPECT_GT(ate.num_poses, 10);
  EXPECT_LE(ate.rmse_m, 0.05);
  EXPECT_EQ(map.keyframes.size(), a.slam->keyframes().size());  // nothing added
  std::printf(
      "localize: first fix after %.2f m (%.1f s), %zu keyframes, %d with fixes, %d false; "
      "ATE while tracking %.2f cm over %d poses; %.2f s localising vs %.2f s mapping the map run\n",
      run.first_fix_path_m, run.first_fix_time_s, run.keyframes.size(), fixes, false_fixes,
      ate.rmse_m * 100, ate.num_poses, run.processing_s, a.processing_s);
}

TEST(LocalizerTest, RunOutsideTheMapReportsLost) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config = ShortSessionConfig();
  config.simulator.route.depart_distance_m = 3.0;
  const Config& config_b = config;
  // Another room (the bundled seed_hall), never seen by the map.
  const std::string hall = std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml";
  const std::string lidar = ::uwbsar::testing::SeedLabLidarMap();
  const slam::MapRun a = slam::MapSimulation(config, lidar, "depart-return", 1);
  const SessionData map = slam::CaptureSession(a);
  const slam::LocalizeRun run =
      slam::LocalizeSimulation(map, config_b, hall, "depart-return", 1, 2);
  EXPECT_EQ(run.first_fix, -1);
  for (const LocalizedKeyframe& k : run.keyframes) {
    EXPECT_EQ(k.status, LocalizeStatus::kLost) << "keyframe " << k.id;
  }
}

}  // namespace
}  // namespace uwbsar
