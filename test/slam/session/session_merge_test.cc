// Joining runs (points 2 and 4) on short simulated seed_lab runs: a second run
// that starts 2 m further along and 20 deg turned (another seed) is placed in the saved map
// within 3 m of travel, with no false loop, both runs within 5 cm ATE in the common frame;
// a run that never sees the saved map is not connected.
#include "slam/session/session_merge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "slam/app_config.h"
#include "slam/map_job.h"
#include "slam/outputs/session_capture.h"
#include "slam/outputs/session_outputs.h"
#include "slam/scene_simulation.h"
#include "slam/session/session_file.h"
#include "test/shared_data.h"
#include "test/slam/session/session_test_util.h"

namespace uwbsar {
namespace {

constexpr double kFalseLoopM = 0.2;
constexpr double kFalseLoopDeg = 5.0;

/// The true pose of each keyframe's anchor (the anchor is rigid to the robot at its stamp).
std::map<int, Pose2> TrueAnchors(const SessionData& s, int trajectory,
                                 const std::vector<OdometrySample>& gt, int id_offset) {
  std::map<int, Pose2> out;
  for (const SessionKeyframe& k : s.keyframes) {
    if (k.trajectory != trajectory) continue;
    out[k.id + id_offset] = ::uwbsar::testing::NearestGroundTruth(gt, k.stamp_ns).T_world_robot *
                            (k.T_odom_robot.Inverse() * k.T_odom_anchor);
  }
  return out;
}

using ::uwbsar::testing::ShortSessionConfig;

/// Run A (ShortSessionConfig, seed 1) and run B 2 m along and 20 deg turned (seed 2) in the
/// seed_lab scene, each captured as a session.
struct SeedLabRuns {
  Config config_a = ShortSessionConfig();
  Config config_b = ::uwbsar::testing::TurnedRevisitConfig(config_a);
  slam::MapRun a, b;
  SessionData sa, sb;

  SeedLabRuns() {
    const std::string map = ::uwbsar::testing::SeedLabLidarMap();
    a = slam::MapSimulation(config_a, map, "depart-return", 1);
    b = slam::MapSimulationInScene(config_b, map, "depart-return", 1, 2,
                                   slam::RouteStart(config_b).Inverse());
    sa = slam::CaptureSession(a);
    sb = slam::CaptureSession(b);
  }
};

TEST(SessionMergeTest, SecondRunTurnedAndShiftedIsPlacedWithinThreeMetresWithoutFalseLoops) {
  UWBSAR_NEED_SEED_LAB_MAP();
  SeedLabRuns runs;
  Config& config_a = runs.config_a;
  const slam::MapRun &a = runs.a, &b = runs.b;
  const SessionData &sa = runs.sa, &sb = runs.sb;
  // Every view kept, so that the loops between the runs stay in the joined session to be judged
  // (a retired keyframe's loops leave with it: RevisitedViewsAreRetired... below).
  config_a.slam.place_views.max_per_place = 0;
  MergeReport report;
  const SessionData merged = MergeSessions(sa, sb, config_a, &report);
  ASSERT_TRUE(report.connected) << report.reason;
  EXPECT_LE(report.connect_path_m, 3.0);

  // Every loop between the runs against the truth.
  std::map<int, Pose2> truth = TrueAnchors(sa, 0, a.ground_truth, 0);
  for (const auto& [id, p] : TrueAnchors(sb, 0, b.ground_truth, report.id_offset)) truth[id] = p;
  int between = 0, false_loops = 0;
  for (const SessionLoop& l : merged.loops) {
    if (!l.accepted || l.reason != "between sessions") continue;
    ++between;
    const Pose2 t = Between(truth.at(l.match_id), truth.at(l.query_id));
    const double err_m = std::hypot(l.T_ij.x_m - t.x_m, l.T_ij.y_m - t.y_m);
    const double err_deg = std::abs(NormalizeAngle(l.T_ij.yaw_rad - t.yaw_rad)) * 180 / M_PI;
    false_loops += err_m > kFalseLoopM || err_deg > kFalseLoopDeg;
  }
  EXPECT_GE(between, 2);
  EXPECT_EQ(false_loops, 0);

  std::map<int, std::vector<OdometrySample>> gt = {{0, a.ground_truth},
                                                   {report.trajectory_offset, b.ground_truth}};
  const AteResult common = slam::CommonFrameError(merged, gt);
  const AteResult alone_a = slam::TrajectoryError(a.slam->CorrectedTrajectory(), a.ground_truth);
  EXPECT_LE(common.rmse_m, 0.05);
  // session.freeze_saved_map (default): the saved map does not move; the run is fitted to it.
  ASSERT_TRUE(config_a.session.freeze_saved_map);
  EXPECT_EQ(report.retired, 0);
  for (const SessionKeyframe& k : sa.keyframes) {
    const SessionKeyframe* after = merged.Find(k.id);
    ASSERT_NE(after, nullptr);
    EXPECT_EQ(after->T_map_anchor.x_m, k.T_map_anchor.x_m);
    EXPECT_EQ(after->T_map_anchor.y_m, k.T_map_anchor.y_m);
    EXPECT_EQ(after->T_map_anchor.yaw_rad, k.T_map_anchor.yaw_rad);
  }
  // Optimised together, the saved map moves, and both runs still agree within 5 cm.
  Config together = config_a;
  together.session.freeze_saved_map = false;
  MergeReport report_together;
  const SessionData joint = MergeSessions(sa, sb, together, &report_together);
  ASSERT_TRUE(report_together.connected);
  double moved_m = 0.0;
  for (const SessionKeyframe& k : sa.keyframes) {
    const Pose2 d = Between(k.T_map_anchor, joint.Find(k.id)->T_map_anchor);
    moved_m = std::max(moved_m, std::hypot(d.x_m, d.y_m));
  }
  EXPECT_GT(moved_m, 1e-4);
  EXPECT_LE(slam::CommonFrameError(joint, gt).rmse_m, 0.05);
  std::printf(
      "merge: placed after %.2f m of the second run (keyframe %d), %d keyframe pairs matched, "
      "%d validated, %d loops between the runs (%d rejected, %d dropped), %d false; "
      "ATE common frame %.2f cm (run A alone %.2f cm)\n",
      report.connect_path_m, report.connect_keyframe_id, report.candidates, report.validated,
      report.loop_edges, report.loop_edges_rejected, report.dropped, false_loops,
      common.rmse_m * 100, alone_a.rmse_m * 100);
}

/// The map resumed every day keeps what one run would: the new run's keyframes retire the
/// saved views of the places they revisit (join_retirement.h), and both runs' trajectories
/// stay corrected through the retired keyframes' anchors, also once saved and read back.
TEST(SessionMergeTest, RevisitedViewsAreRetiredAndBothRunsStayCorrected) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const SeedLabRuns runs;
  const Config& config_a = runs.config_a;
  ASSERT_EQ(config_a.slam.place_views.max_per_place, 1);
  const slam::MapRun &a = runs.a, &b = runs.b;
  const SessionData &sa = runs.sa, &sb = runs.sb;
  MergeReport report;
  const SessionData merged = MergeSessions(sa, sb, config_a, &report);
  ASSERT_TRUE(report.connected) << report.reason;
  EXPECT_GT(report.retired, 0);
  EXPECT_EQ(merged.keyframes.size() + static_cast<std::size_t>(report.retired),
            sa.keyframes.size() + sb.keyframes.size());
  EXPECT_EQ(merged.anchors.size(),
            sa.anchors.size() + sb.anchors.size() + static_cast<std::size_t>(report.retired));
  // Only saved views are retired (the newer view wins), and every anchor follows a kept one.
  int saved_retired = 0;
  for (const SessionKeyframe& k : sa.keyframes) saved_retired += merged.Find(k.id) == nullptr;
  EXPECT_EQ(saved_retired, report.retired);
  for (const SessionAnchor& x : merged.anchors) {
    EXPECT_TRUE(x.hub_id < 0 || merged.Find(x.hub_id) != nullptr) << x.id << " -> " << x.hub_id;
  }
  for (const SessionLoop& l : merged.loops) {
    EXPECT_TRUE(merged.Find(l.query_id) && merged.Find(l.match_id));
  }
  std::map<int, std::vector<OdometrySample>> gt = {{0, a.ground_truth},
                                                   {report.trajectory_offset, b.ground_truth}};
  const double joined_cm = slam::CommonFrameError(merged, gt).rmse_m * 100.0;
  Config keep_all = config_a;
  keep_all.slam.place_views.max_per_place = 0;
  MergeReport unused;
  const double kept_cm =
      slam::CommonFrameError(MergeSessions(sa, sb, keep_all, &unused), gt).rmse_m * 100.0;
  EXPECT_LE(joined_cm, 5.0);
  EXPECT_LE(joined_cm, kept_cm + 0.5);
  // Saved and read back: the same trajectories.
  const std::string path = ::testing::TempDir() + "/uwbsar_retired_join.uwbsar";
  WriteSession(path, merged);
  const SessionData read = ReadSession(path);
  EXPECT_NEAR(slam::CommonFrameError(read, gt).rmse_m * 100.0, joined_cm, 0.01);
  std::printf(
      "join with retirement: %zu + %zu keyframes -> %zu (%d retired); ATE common frame "
      "%.2f cm (every view kept: %.2f cm)\n",
      sa.keyframes.size(), sb.keyframes.size(), merged.keyframes.size(), report.retired, joined_cm,
      kept_cm);
}

TEST(SessionMergeTest, LoopsOfOneNewKeyframeShareItsInformation) {
  std::vector<PoseGraphEdge> loops(4);
  const int to_ids[] = {7, 7, 7, 9};  // keyframe 7 matched three saved ones, 9 one
  for (int i = 0; i < 4; ++i) {
    loops[i].from_id = i;
    loops[i].to_id = to_ids[i];
    loops[i].information = Eigen::Matrix3d::Identity() * 300.0 * (i + 1);
  }
  ShareLoopInformationPerKeyframe(&loops);
  EXPECT_DOUBLE_EQ(loops[0].information(0, 0), 100.0);
  EXPECT_DOUBLE_EQ(loops[1].information(1, 1), 200.0);
  EXPECT_DOUBLE_EQ(loops[2].information(2, 2), 300.0);
  EXPECT_DOUBLE_EQ(loops[2].information(0, 1), 0.0);
  EXPECT_DOUBLE_EQ(loops[3].information(0, 0), 1200.0);  // alone: unchanged
}

TEST(SessionMergeTest, RunThatNeverSeesTheMapIsNotConnected) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config_a = ShortSessionConfig();
  config_a.simulator.route.depart_distance_m = 3.0;
  const Config& config_b = config_a;
  // Another room (the bundled seed_hall), never seen by A.
  const std::string hall = std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml";
  const std::string map = ::uwbsar::testing::SeedLabLidarMap();
  const slam::MapRun a = slam::MapSimulation(config_a, map, "depart-return", 1);
  const slam::MapRun b = slam::MapSimulationInScene(config_b, hall, "depart-return", 1, 2);
  MergeReport report;
  const SessionData merged =
      MergeSessions(slam::CaptureSession(a), slam::CaptureSession(b), config_a, &report);
  EXPECT_FALSE(report.connected);
  EXPECT_FALSE(report.reason.empty());
  EXPECT_EQ(merged.keyframes.size(), a.slam->keyframes().size());
}

}  // namespace
}  // namespace uwbsar
