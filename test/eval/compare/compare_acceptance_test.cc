// The SAR map of the simulated seed_lab depart-and-return run against
// the seed_lab LiDAR grid (paper: cell-wise difference 1397 / 16800 = 8.3 %), and the same run
// mapped from odometry alone, which must score visibly worse. Runs the real CLI end to end.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "test/cli_runner.h"
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
  // Odometry only: no keyframe is ever a loop candidate.
  std::ofstream(dir + "/odometry_only.yaml")
      << "place_recognition:\n  candidates:\n    exclude_recent_path_m: 1000000.0\n";
  RunUwbsar("--config " + dir + "/odometry_only.yaml map " + dir + "/bag --out " + dir + "/odom");
  const nlohmann::json slam = Compare(dir + "/slam/map.yaml", dir + "/cmp_slam");
  const nlohmann::json odom = Compare(dir + "/odom/map.yaml", dir + "/cmp_odom");
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
