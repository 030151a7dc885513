// Keyframes bounded by the area mapped (slam/session/place_views.h): the office ring driven three
// times in one run keeps about one lap's keyframes, closes every lap with no false loop, is as
// accurate as keeping every keyframe, and saves a session that reads back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "slam/app_config.h"
#include "slam/map_job.h"
#include "slam/outputs/session_capture.h"
#include "slam/outputs/session_outputs.h"
#include "slam/session/session_file.h"
#include "slam/slam_system.h"

namespace uwbsar {
namespace {

std::string OfficeFile(const std::string& name) {
  return std::string(UWBSAR_SOURCE_DIR) + "/config/maps/office/" + name;
}

/// The office ring (14,9 -> 4,9 -> 4,4 -> 16,4 -> 16,9 -> 14,9) `laps` times.
std::string RingRoute(int laps) {
  const std::string path = ::testing::TempDir() + "office_ring_x" + std::to_string(laps) + ".txt";
  std::ofstream out(path);
  out << "14 9\n";
  for (int k = 0; k < laps; ++k) out << "4 9\n4 4\n16 4\n16 9\n14 9\n";
  return path;
}

Pose2 TruePoseAt(const std::vector<OdometrySample>& truth, TimestampNs t) {
  auto it = std::lower_bound(truth.begin(), truth.end(), t,
                             [](const OdometrySample& s, TimestampNs u) { return s.stamp_ns < u; });
  if (it == truth.end()) --it;
  return it->T_world_robot;
}

struct RunFigures {
  std::size_t kept = 0, retired = 0;
  int accepted = 0, false_accepted = 0;
  double ate_m = 0.0, odometry_ate_m = 0.0;
};

RunFigures Figures(const slam::MapRun& run) {
  RunFigures f;
  f.kept = run.slam->keyframes().size();
  f.retired = run.slam->retired().size();
  std::map<int, Pose2> true_anchor;
  for (const slam::KeyframeRecord& k : run.slam->keyframes()) {
    true_anchor[k.keyframe.id] = TruePoseAt(run.ground_truth, k.keyframe.stamp_ns) *
                                 (k.keyframe.T_world_robot.Inverse() * k.keyframe.T_world_anchor);
  }
  for (const slam::RetiredKeyframe& k : run.slam->retired()) {
    true_anchor[k.id] =
        TruePoseAt(run.ground_truth, k.stamp_ns) * (k.T_odom_robot.Inverse() * k.T_odom_anchor);
  }
  for (const slam::LoopRecord& l : run.slam->loops()) {
    if (!l.accepted()) continue;
    ++f.accepted;
    const Pose2 truth = Between(true_anchor.at(l.match_id), true_anchor.at(l.query_id));
    const Pose2& T = l.validation.constraint.T_ij;
    f.false_accepted += std::hypot(T.x_m - truth.x_m, T.y_m - truth.y_m) > 0.2 ||
                        std::abs(NormalizeAngle(T.yaw_rad - truth.yaw_rad)) > 5.0 * M_PI / 180.0;
  }
  std::vector<std::pair<TimestampNs, Pose2>> odometry;
  for (const OdometryEntry& e : run.slam->odometry())
    odometry.push_back({e.stamp_ns, e.T_world_robot});
  f.ate_m = slam::TrajectoryError(run.slam->CorrectedTrajectory(), run.ground_truth).rmse_m;
  f.odometry_ate_m = slam::TrajectoryError(odometry, run.ground_truth).rmse_m;
  return f;
}

TEST(WorkdayRunTest, ThreeLapsKeepAboutOneLapOfKeyframesAndLoseNoAccuracy) {
  const std::string route = RingRoute(3);
  Config bounded;  // the default: one view per place
  Config everything;
  everything.slam.place_views.max_per_place = 0;
  const slam::MapRun a = slam::MapSimulation(bounded, OfficeFile("office.yaml"), route, 3);
  const slam::MapRun b = slam::MapSimulation(everything, OfficeFile("office.yaml"), route, 3);
  const RunFigures fa = Figures(a), fb = Figures(b);
  for (const auto& [name, f] : {std::pair{"one view per place", fa}, {"every keyframe", fb}}) {
    std::printf("%s: %zu kept, %zu retired, %d loops (%d false), ATE %.2f cm, odometry %.2f cm\n",
                name, f.kept, f.retired, f.accepted, f.false_accepted, f.ate_m * 100,
                f.odometry_ate_m * 100);
  }
  ASSERT_EQ(fb.retired, 0u);
  // About 34 keyframes a lap: the second and third laps replace the first's instead of adding.
  EXPECT_GT(fa.retired, fb.kept / 2);
  EXPECT_LT(fa.kept, fb.kept / 2);
  EXPECT_EQ(fa.false_accepted, 0);
  EXPECT_GT(fa.accepted, 0);
  EXPECT_LE(fa.ate_m, 0.05);
  EXPECT_LE(fa.ate_m, fb.ate_m + 0.005);

  // The session of the bounded map holds the kept keyframes, the folded edges, and reads back.
  const std::string path = ::testing::TempDir() + "workday_session.uwbsar";
  WriteSession(path, slam::CaptureSession(a));
  const SessionData read = ReadSession(path);
  EXPECT_EQ(read.keyframes.size(), fa.kept);
  EXPECT_TRUE(std::any_of(read.edges.begin(), read.edges.end(),
                          [](const SessionEdge& e) { return e.edge.kind == EdgeKind::kMarginal; }));
  for (const SessionLoop& l : read.loops) {
    EXPECT_NE(read.Find(l.query_id), nullptr);
    EXPECT_NE(read.Find(l.match_id), nullptr);
  }
  // The retired keyframes come back as anchors, so the saved run's trajectory (what a later
  // `map --resume` or `merge` writes for it) is as corrected as the run's own.
  EXPECT_EQ(read.anchors.size(), fa.retired);
  const double saved_ate_m =
      slam::TrajectoryError(slam::CorrectedTrajectory(read, 0), a.ground_truth).rmse_m;
  std::printf("saved run's trajectory: ATE %.2f cm (the run's %.2f cm)\n", saved_ate_m * 100,
              fa.ate_m * 100);
  EXPECT_LE(saved_ate_m, fa.ate_m + 0.002);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace uwbsar
