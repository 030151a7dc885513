// The paper's experiment on a simulated depart-and-return run
// in seed_lab. D_i -> R_i are all accepted, no D_i -> R_j with |i - j| >= 2 is, and each
// accepted fused transform is within 3 cm and 1 deg of the ground truth.
#include <gtest/gtest.h>

#include <cstdio>

#include "eval/region_study.h"
#include "slam/app_config.h"
#include "test/frontend/place_recognition/sim_run.h"
#include "test/shared_data.h"

namespace uwbsar::testing {
namespace {

/// The scan of `pass` nearest to the centre of `region` (world frame).
const ImagedScan& ScanNear(const std::vector<ImagedScan>& pass, const StudyRegion& region) {
  const Point2 c =
      region.grid.PixelToMetric(0.5 * (region.grid.cols - 1), 0.5 * (region.grid.rows - 1));
  const ImagedScan* best = &pass.front();
  double best_d = 1e18;
  for (const ImagedScan& s : pass) {
    const double d = std::abs(s.T_world_robot.x_m - c.x_m) + std::abs(s.T_world_robot.y_m - c.y_m);
    if (d < best_d) {
      best_d = d;
      best = &s;
    }
  }
  return *best;
}

TEST(RegionStudyAcceptanceTest, SeedLabDepartReturnFindsEveryLoopAndNoFalseOne) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config;
  const SimulatedRun run = SimulateAndImage(config, SeedLabMap(), "depart-return", 4);
  const std::size_t turn = TurnaroundIndex(run.scans);
  const std::vector<ImagedScan> depart(run.scans.begin(), run.scans.begin() + turn);
  const std::vector<ImagedScan> back(run.scans.begin() + turn, run.scans.end());
  std::vector<SensorGeometry> sensors;
  for (const RadarConfig& r : config.radars)
    sensors.push_back(SensorGeometry::FromConfig(r, config.pulse));
  const RegionStudy study = RunRegionStudy(depart, back, sensors, config, RegionStudyOptions{});
  ASSERT_GE(study.d_regions.size(), 5u);
  int loops = 0, false_loops = 0;
  double worst_xy = 0, worst_yaw = 0;
  for (const RegionPair& p : study.pairs) {
    const bool accepted = p.validation.accepted;
    const auto& ma = p.matches.at(DetectorKind::kAkaze);
    const auto& mo = p.matches.at(DetectorKind::kOrb);
    std::printf("[A] D%d -> R%d: AKAZE %3d/%3d ORB %3d/%3d %s", p.d, p.r, ma.good_matches,
                ma.ratio_matches, mo.good_matches, mo.ratio_matches,
                accepted ? "accepted" : p.validation.reason.c_str());
    if (p.d == p.r) {
      EXPECT_TRUE(accepted) << "D" << p.d << " -> R" << p.r << ": " << p.validation.reason;
      ++loops;
    }
    if (std::abs(p.d - p.r) >= 2) {
      EXPECT_FALSE(accepted) << "D" << p.d << " -> R" << p.r;
      false_loops += accepted;
    }
    if (accepted) {
      const StudyRegion& d =
          study.d_regions.at(static_cast<std::size_t>(p.d - study.d_regions.front().index));
      const StudyRegion& r =
          study.r_regions.at(static_cast<std::size_t>(p.r - study.r_regions.front().index));
      const Pose2 truth = OdometryErrorAt(run, ScanNear(depart, d)) *
                          OdometryErrorAt(run, ScanNear(back, r)).Inverse();
      const Pose2 e = Between(truth, p.validation.constraint.T_ij);
      const double xy = std::hypot(e.x_m, e.y_m), yaw = std::abs(e.yaw_rad) * 180 / M_PI;
      std::printf("  error %.1f mm %.2f deg", xy * 1e3, yaw);
      if (p.d == p.r) {
        worst_xy = std::max(worst_xy, xy);
        worst_yaw = std::max(worst_yaw, yaw);
        EXPECT_LT(xy, 0.03);
        EXPECT_LT(yaw, 1.0);
      }
    }
    std::printf("\n");
  }
  std::printf(
      "[A] %zu regions, %d loops D_i -> R_i, %d false loops, worst error %.1f mm %.2f deg\n",
      study.d_regions.size(), loops, false_loops, worst_xy * 1e3, worst_yaw);
}

}  // namespace
}  // namespace uwbsar::testing
