// End-to-end acceptance of the SLAM pipeline on simulated runs.
#include "slam/slam_system.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "slam/app_config.h"
#include "slam/map_job.h"
#include "test/shared_data.h"

namespace uwbsar {
namespace {

std::string SeedLab() { return ::uwbsar::testing::SeedLabLidarMap(); }

TEST(SlamSystemTest, SeedLabDepartReturnBeatsOdometryByThreeTimes) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const Config config;
  const slam::MapRun run = slam::MapSimulation(config, SeedLab(), "depart-return", 1);
  std::vector<std::pair<TimestampNs, Pose2>> odometry;
  for (const OdometryEntry& e : run.slam->odometry())
    odometry.push_back({e.stamp_ns, e.T_world_robot});
  const AteResult slam = slam::TrajectoryError(run.slam->CorrectedTrajectory(), run.ground_truth);
  const AteResult odom = slam::TrajectoryError(odometry, run.ground_truth);
  // True anchor poses: the anchor is rigidly attached to the robot at the tile's start.
  auto true_pose_at = [&](TimestampNs t) {
    const OdometrySample* best = &run.ground_truth.front();
    for (const auto& g : run.ground_truth) {
      if (std::llabs(g.stamp_ns - t) < std::llabs(best->stamp_ns - t)) best = &g;
    }
    return best->T_world_robot;
  };
  std::map<int, Pose2> true_anchor;
  for (const slam::KeyframeRecord& k : run.slam->keyframes()) {
    const Pose2 T_robot_anchor = k.keyframe.T_world_robot.Inverse() * k.keyframe.T_world_anchor;
    true_anchor[k.keyframe.id] = true_pose_at(k.keyframe.stamp_ns) * T_robot_anchor;
  }
  int accepted = 0;
  double worst_loop_m = 0.0;
  for (const slam::LoopRecord& l : run.slam->loops()) {
    accepted += l.accepted();
    if (!l.validation.accepted) continue;
    const Pose2 truth = Between(true_anchor[l.match_id], true_anchor[l.query_id]);
    const Pose2& T = l.validation.constraint.T_ij;
    const double err = std::hypot(T.x_m - truth.x_m, T.y_m - truth.y_m);
    worst_loop_m = std::max(worst_loop_m, err);
    std::printf("loop %d -> %d: akaze %d orb %d, error %.1f mm %.2f deg, backend %s chi2 %.2f\n",
                l.match_id, l.query_id, l.Match(DetectorKind::kAkaze).good_matches,
                l.Match(DetectorKind::kOrb).good_matches, err * 1e3,
                NormalizeAngle(T.yaw_rad - truth.yaw_rad) * 180 / M_PI,
                l.rejected_by_backend ? "rejected" : "accepted", l.chi2);
  }
  const slam::StageTimes& t = run.slam->times();
  std::printf(
      "keyframes %zu, candidates %zu, loops accepted %d; ATE %.2f cm, odometry %.2f cm; "
      "log %.1f s processed in %.2f s (imaging %.2f, features %.2f, matching %.2f, "
      "optimisation %.2f)\n",
      run.slam->keyframes().size(), run.slam->loops().size(), accepted, slam.rmse_m * 100,
      odom.rmse_m * 100, run.log_duration_s(), run.processing_s, t.imaging_s, t.features_s,
      t.matching_s, t.optimization_s);
  EXPECT_GT(accepted, 0);
  EXPECT_LT(worst_loop_m, 0.03);  // every accepted loop within 3 cm of the truth
  EXPECT_LE(slam.rmse_m, 0.05);
  EXPECT_LE(3.0 * slam.rmse_m, odom.rmse_m);
}

// The keyframe thread changes who does the work, not the result: the frontend never
// reads the graph and the worker takes keyframes in order.
TEST(SlamSystemTest, KeyframeThreadGivesTheSameResultAsOneThread) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config threaded;
  threaded.slam.keyframe_thread = true;
  threaded.slam.keyframe_queue_size = 2;  // the feeder also waits on a full queue
  Config inline_config = threaded;
  inline_config.slam.keyframe_thread = false;
  const slam::MapRun a = slam::MapSimulation(threaded, SeedLab(), "depart-return", 1);
  const slam::MapRun b = slam::MapSimulation(inline_config, SeedLab(), "depart-return", 1);
  ASSERT_EQ(a.slam->keyframes().size(), b.slam->keyframes().size());
  ASSERT_EQ(a.slam->loops().size(), b.slam->loops().size());
  for (std::size_t i = 0; i < a.slam->loops().size(); ++i) {
    EXPECT_EQ(a.slam->loops()[i].match_id, b.slam->loops()[i].match_id);
    EXPECT_EQ(a.slam->loops()[i].query_id, b.slam->loops()[i].query_id);
    EXPECT_EQ(a.slam->loops()[i].accepted(), b.slam->loops()[i].accepted());
  }
  const auto ta = a.slam->CorrectedTrajectory();
  const auto tb = b.slam->CorrectedTrajectory();
  ASSERT_EQ(ta.size(), tb.size());
  ASSERT_FALSE(ta.empty());
  for (std::size_t i = 0; i < ta.size(); ++i) {
    ASSERT_EQ(ta[i].first, tb[i].first);
    ASSERT_EQ(ta[i].second.x_m, tb[i].second.x_m) << i;
    ASSERT_EQ(ta[i].second.y_m, tb[i].second.y_m) << i;
    ASSERT_EQ(ta[i].second.yaw_rad, tb[i].second.yaw_rad) << i;
  }
}

}  // namespace
}  // namespace uwbsar
