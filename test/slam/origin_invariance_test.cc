// Results must not depend on where the world origin is. Real robots
// map in frames far from 0 (UTM, building coordinates); the same run with odometry and
// ground truth shifted by a constant must give the same loops and the same ATE.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <utility>
#include <vector>

#include "core/message.h"
#include "drivers/sim/sim_source.h"
#include "slam/app_config.h"
#include "slam/map_job.h"
#include "slam/slam_system.h"
#include "test/shared_data.h"

namespace uwbsar {
namespace {

std::string SeedLab() { return testing::SeedLabLidarMap(); }

struct Outcome {
  std::set<std::pair<int, int>> accepted_loops;  ///< (match_id, query_id)
  std::size_t keyframes = 0;
  std::size_t candidates = 0;
  AteResult ate;
  std::vector<std::pair<TimestampNs, Pose2>> trajectory;  ///< shifted back by the offset
};

/// Replays recorded messages with every odometry and ground-truth pose moved by
/// (dx_m, dy_m): the same run, only the world origin is elsewhere.
class ShiftedReplay : public MessageSource {
 public:
  ShiftedReplay(const std::vector<Message>& messages, double dx_m, double dy_m)
      : messages_(messages), dx_m_(dx_m), dy_m_(dy_m) {}
  void Run(const MessageSink& sink) override {
    for (Message m : messages_) {
      m.odometry.T_world_robot.x_m += dx_m_;  // odometry and ground truth; unused for scans
      m.odometry.T_world_robot.y_m += dy_m_;
      sink(m);
    }
  }

 private:
  const std::vector<Message>& messages_;
  double dx_m_, dy_m_;
};

/// Maps the recorded messages shifted by (dx_m, dy_m).
Outcome MapShifted(const Config& config, const std::vector<Message>& messages, double dx_m,
                   double dy_m) {
  ShiftedReplay source(messages, dx_m, dy_m);
  const slam::MapRun run = slam::MapSource(config, "shifted", source);
  Outcome out;
  out.keyframes = run.slam->keyframes().size();
  out.candidates = run.slam->loops().size();
  for (const slam::LoopRecord& l : run.slam->loops()) {
    if (l.accepted()) out.accepted_loops.insert({l.match_id, l.query_id});
  }
  const auto trajectory = run.slam->CorrectedTrajectory();
  out.ate = slam::TrajectoryError(trajectory, run.ground_truth);
  for (const auto& [stamp, pose] : trajectory) {
    out.trajectory.push_back({stamp, {pose.x_m - dx_m, pose.y_m - dy_m, pose.yaw_rad}});
  }
  return out;
}

TEST(OriginInvarianceTest, ShiftedWorldOriginGivesTheSameLoopsAndAte) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const Config config;
  // One simulated run, recorded once and replayed at every offset.
  const sim::SimScenario scenario = sim::MakeScenario(config, SeedLab(), "depart-return", 1);
  std::vector<Message> messages;
  sim::SimSource(config, scenario, 1).Run([&](const Message& m) { messages.push_back(m); });

  const Outcome base = MapShifted(config, messages, 0.0, 0.0);
  std::printf("origin 0: %zu keyframes, %zu candidates, %zu loops, ATE %.3f cm\n", base.keyframes,
              base.candidates, base.accepted_loops.size(), base.ate.rmse_m * 100);
  ASSERT_GT(base.accepted_loops.size(), 0u);
  for (const double offset_m : {1e2, 1e4, 1e6}) {
    // Different offsets in x and y, one negative (lattice indices below zero).
    const Outcome shifted = MapShifted(config, messages, offset_m, -0.75 * offset_m);
    std::printf("origin %.0e m: %zu keyframes, %zu candidates, %zu loops, ATE %.3f cm\n", offset_m,
                shifted.keyframes, shifted.candidates, shifted.accepted_loops.size(),
                shifted.ate.rmse_m * 100);
    EXPECT_EQ(shifted.keyframes, base.keyframes) << offset_m;
    EXPECT_EQ(shifted.accepted_loops, base.accepted_loops) << offset_m;
    EXPECT_NEAR(shifted.ate.rmse_m, base.ate.rmse_m, 1e-3) << offset_m;
    ASSERT_EQ(shifted.trajectory.size(), base.trajectory.size()) << offset_m;
    double worst_m = 0.0;
    for (std::size_t i = 0; i < base.trajectory.size(); ++i) {
      const Pose2& a = base.trajectory[i].second;
      const Pose2& b = shifted.trajectory[i].second;
      worst_m = std::max(worst_m, std::hypot(a.x_m - b.x_m, a.y_m - b.y_m));
    }
    std::printf("  worst trajectory difference %.3g mm\n", worst_m * 1e3);
    EXPECT_LT(worst_m, 1e-3) << offset_m;
  }
}

}  // namespace
}  // namespace uwbsar
