// The SAR map of the simulated seed_lab depart-and-return run against
// the seed_lab LiDAR grid (paper: cell-wise difference 1397 / 16800 = 8.3 %), and the same run
// mapped from odometry alone, which must score visibly worse. Runs the real CLI end to end.
// The paper's figures come from its intensity rule (`compare` of map_grid.yaml); map.pgm, the
// navigation grid, is scored beside them and checked as a planner uses it (issue 29).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "imaging/occupancy_grid.h"
#include "test/cli_runner.h"
#include "test/navigation_checks.h"
#include "test/shared_data.h"
#include "test_maps.h"

namespace uwbsar {
namespace {

std::string RunUwbsar(const std::string& args) {
  const testing::CliRun run = testing::Uwbsar(args);
  EXPECT_EQ(run.exit_code, 0) << args << "\n" << run.output;
  return run.output;
}

nlohmann::json Compare(const std::string& map_yaml, const std::string& out_dir) {
  RunUwbsar("compare " + map_yaml + " " + testing::SeedLabYaml() + " --out " + out_dir);
  std::ifstream in(out_dir + "/metrics.json");
  return nlohmann::json::parse(in);
}

TEST(CompareAcceptanceTest, SeedLabSlamMapMatchesLidarAndBeatsOdometryOnly) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const std::string dir = testing::FreshDir("acceptance_b");
  RunUwbsar("simulate --map " + testing::SeedLabYaml() + " --route depart-return --out " + dir +
            "/bag");
  RunUwbsar("map " + dir + "/bag --out " + dir + "/slam");
  // Odometry only: no keyframe is ever a loop candidate, no wall ties keyframes (wall
  // edges and landmarks straighten a corridor without a loop), and the odometry is taken as the
  // base reports it (no calibration, no gyro bias measured at the standstills).
  std::ofstream(dir + "/odometry_only.yaml")
      << "place_recognition:\n  candidates:\n    exclude_recent_path_m: 1000000.0\n"
      << "  wall_profiles:\n    enabled: false\n"
      << "backend:\n  odometry_calibration: false\n";
  RunUwbsar("--config " + dir + "/odometry_only.yaml map " + dir + "/bag --out " + dir + "/odom");
  const nlohmann::json slam = Compare(dir + "/slam/map_grid.yaml", dir + "/cmp_slam");
  const nlohmann::json odom = Compare(dir + "/odom/map_grid.yaml", dir + "/cmp_odom");
  const nlohmann::json nav = Compare(dir + "/slam/map.yaml", dir + "/cmp_nav");
  const auto& n = nav["metrics"];
  std::printf("map.pgm (navigation grid): difference %.1f %% (paper's counting %.1f %%), F1 %.3f\n",
              100 * n["difference_ratio"].get<double>(),
              100 * n["paper_difference_ratio"].get<double>(), n["f1"].get<double>());
  testing::ExpectNavigationMap("seed_lab", LoadOccupancyGrid(dir + "/slam/map.yaml"),
                               testing::SeedLabGrid(),
                               testing::ReadTumPoses(dir + "/slam/trajectory.tum"),
                               testing::ReadTumPoses(dir + "/slam/ground_truth.tum"));
  const auto& s = slam["metrics"];
  const auto& o = odom["metrics"];
  std::printf("SLAM:     difference %.1f %% (paper's rule %.1f %%), F1 %.3f, SAR->LiDAR %.3f m\n",
              100 * s["difference_ratio"].get<double>(),
              100 * s["paper_difference_ratio"].get<double>(), s["f1"].get<double>(),
              s["sar_to_lidar"]["mean_m"].get<double>());
  std::printf("odometry: difference %.1f %% (paper's rule %.1f %%), F1 %.3f, SAR->LiDAR %.3f m\n",
              100 * o["difference_ratio"].get<double>(),
              100 * o["paper_difference_ratio"].get<double>(), o["f1"].get<double>(),
              o["sar_to_lidar"]["mean_m"].get<double>());
  EXPECT_TRUE(slam["alignment"]["accepted"].get<bool>());
  EXPECT_LE(s["paper_difference_ratio"].get<double>(), 0.09);
  EXPECT_GT(s["f1"].get<double>(), 0.8);
  // The metric separates the good map from the bad one on every count.
  EXPECT_LT(s["difference_ratio"].get<double>(), o["difference_ratio"].get<double>() - 0.01);
  EXPECT_LT(s["paper_difference_ratio"].get<double>(), o["paper_difference_ratio"].get<double>());
  EXPECT_GT(s["f1"].get<double>(), o["f1"].get<double>() + 0.03);
  EXPECT_LT(s["sar_to_lidar"]["mean_m"].get<double>(), o["sar_to_lidar"]["mean_m"].get<double>());
}

}  // namespace
}  // namespace uwbsar
