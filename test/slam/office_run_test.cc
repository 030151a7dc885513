// A longer simulated run with several loops through an office
// floor (config/maps/office: corridor ring driven twice plus a detour into a room,
// about 75 m): no false loop accepted, ATE RMSE <= 10 cm.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "backend/occupancy_io.h"
#include "slam/app_config.h"
#include "slam/map_job.h"
#include "slam/outputs/navigation_map.h"
#include "slam/slam_system.h"
#include "test/navigation_checks.h"

namespace uwbsar {
namespace {

std::string OfficeFile(const std::string& name) {
  return std::string(UWBSAR_SOURCE_DIR) + "/config/maps/office/" + name;
}

// A loop whose transform is farther than this from the truth counts as false.
constexpr double kFalseLoopM = 0.2;
constexpr double kFalseLoopDeg = 5.0;

TEST(OfficeRunTest, SeveralLoopsNoFalseLoopAndAteWithinTenCentimetres) {
  Config config;
  config.simulator.route.clearance_m = 0.3;  // the route keeps 0.3 m from every obstacle
  const auto t0 = std::chrono::steady_clock::now();
  const slam::MapRun run = slam::MapSimulation(config, OfficeFile("office.yaml"),
                                               OfficeFile("route_loops.txt"), /*seed=*/1);
  const double total_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double travel_m = 0.0;  // true path length
  for (std::size_t i = 1; i < run.ground_truth.size(); ++i) {
    const Pose2& a = run.ground_truth[i - 1].T_world_robot;
    const Pose2& b = run.ground_truth[i].T_world_robot;
    travel_m += std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
  }
  ASSERT_GE(travel_m, 60.0);

  std::vector<std::pair<TimestampNs, Pose2>> odometry;
  for (const OdometryEntry& e : run.slam->odometry())
    odometry.push_back({e.stamp_ns, e.T_world_robot});
  const AteResult slam = slam::TrajectoryError(run.slam->CorrectedTrajectory(), run.ground_truth);
  const AteResult odom = slam::TrajectoryError(odometry, run.ground_truth);

  // True anchor poses: the anchor is rigidly attached to the robot at the keyframe's stamp.
  auto true_pose_at = [&](TimestampNs t) {
    auto it = std::lower_bound(
        run.ground_truth.begin(), run.ground_truth.end(), t,
        [](const OdometrySample& s, TimestampNs stamp) { return s.stamp_ns < stamp; });
    if (it == run.ground_truth.end()) --it;
    if (it != run.ground_truth.begin() &&
        std::llabs((it - 1)->stamp_ns - t) < std::llabs(it->stamp_ns - t)) {
      --it;
    }
    return it->T_world_robot;
  };
  std::map<int, Pose2> true_anchor;
  for (const slam::KeyframeRecord& k : run.slam->keyframes()) {
    const Pose2 T_robot_anchor = k.keyframe.T_world_robot.Inverse() * k.keyframe.T_world_anchor;
    true_anchor[k.keyframe.id] = true_pose_at(k.keyframe.stamp_ns) * T_robot_anchor;
  }
  for (const slam::RetiredKeyframe& k : run.slam->retired()) {  // the second lap retires views
    true_anchor[k.id] = true_pose_at(k.stamp_ns) * (k.T_odom_robot.Inverse() * k.T_odom_anchor);
  }

  int accepted = 0, validated = 0, false_accepted = 0, false_validated = 0;
  double worst_accepted_m = 0.0;
  for (const slam::LoopRecord& l : run.slam->loops()) {
    if (!l.validation.accepted) continue;
    ++validated;
    accepted += l.accepted();
    const Pose2 truth = Between(true_anchor[l.match_id], true_anchor[l.query_id]);
    const Pose2& T = l.validation.constraint.T_ij;
    const double err_m = std::hypot(T.x_m - truth.x_m, T.y_m - truth.y_m);
    const double err_deg = std::abs(NormalizeAngle(T.yaw_rad - truth.yaw_rad)) * 180.0 / M_PI;
    const bool is_false = err_m > kFalseLoopM || err_deg > kFalseLoopDeg;
    false_validated += is_false;
    if (l.accepted()) {
      false_accepted += is_false;
      worst_accepted_m = std::max(worst_accepted_m, err_m);
    }
    std::printf("loop %d -> %d: akaze %d orb %d, error %.1f mm %.2f deg, backend %s chi2 %.2f%s\n",
                l.match_id, l.query_id, l.Match(DetectorKind::kAkaze).good_matches,
                l.Match(DetectorKind::kOrb).good_matches, err_m * 1e3, err_deg,
                l.rejected_by_backend ? "rejected" : "accepted", l.chi2, is_false ? "  FALSE" : "");
  }
  const double log_s = run.log_duration_s();
  const slam::StageTimes& t = run.slam->times();
  std::printf(
      "office: travel %.1f m, log %.1f s, keyframes %zu, candidates %zu, validated %d "
      "(%d false), accepted %d (%d false, worst %.1f mm)\n",
      travel_m, log_s, run.slam->keyframes().size(), run.slam->loops().size(), validated,
      false_validated, accepted, false_accepted, worst_accepted_m * 1e3);
  std::printf(
      "office: ATE RMSE %.2f cm, odometry ATE %.2f cm; SLAM %.2f s (real-time factor "
      "%.1f; imaging %.2f, features %.2f, matching %.2f, optimisation %.2f), "
      "simulator %.2f s, both %.2f s\n",
      slam.rmse_m * 100, odom.rmse_m * 100, run.processing_s, log_s / run.processing_s, t.imaging_s,
      t.features_s, t.matching_s, t.optimization_s, total_s - run.processing_s, total_s);

  EXPECT_GT(accepted, 0);
  EXPECT_EQ(false_accepted, 0);
  EXPECT_LE(slam.rmse_m, 0.10);
  EXPECT_LT(slam.rmse_m, odom.rmse_m);

  // map.pgm as `uwbsar map` writes it, read back as a planner would (issue 29).
  const auto corrected = run.slam->CorrectedTrajectory();
  const std::string yaml = ::testing::TempDir() + "office_navigation_map.yaml";
  WriteOccupancyGrid(yaml, "office_navigation_map.pgm",
                     slam::RunNavigationGrid(run.slam->Capture(), corrected));
  std::vector<Pose2> slam_path, truth_path;
  for (const auto& [stamp, pose] : corrected) slam_path.push_back(pose);
  for (const OdometrySample& g : run.ground_truth) truth_path.push_back(g.T_world_robot);
  testing::ExpectNavigationMap("office", LoadOccupancyGrid(yaml),
                               LoadOccupancyGrid(OfficeFile("office.yaml")), slam_path, truth_path);
}

}  // namespace
}  // namespace uwbsar
