// A ring closed only after 50 m on a generated building floor
// (config/maps/tours/two_rings.yaml, the west ring of the figure of eight, 55 m), mapped
// with the default configuration: the ring's closure itself is accepted (a loop between
// the tour's start and its end), no false loop, SLAM beats odometry alone, and the wall
// edges of the straight stretches (pipeline/wall_edges.h) measure the sideways offsets to
// within a few centimetres. Measured (seed 1): 9 loops, 87 wall edges (none rejected, error
// 1.2 cm rms, 3.4 cm at most against the truth), ATE 4.29 cm against 12.34 cm of odometry
// (2.9x). Before the wall edges: 6.24 cm (2.0x), as one ring closure cannot tell the heading
// drift per metre from the turns' scale error; the odometry on this short ring is already
// good, so the 3x of the tour bench is not asked here. The full set of tours and seeds is
// `uwbsar_bench --benchmark_filter=Tour`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pipeline/app_config.h"
#include "pipeline/tour_eval.h"

namespace uwbsar {
namespace {

std::string ToursFile(const std::string& name) {
  return std::string(UWBSAR_SOURCE_DIR) + "/config/maps/tours/" + name;
}

TEST(TourRunTest, RingClosedAfterFiftyMetresWithoutFalseLoops) {
  Config config;
  config.simulator.route.clearance_m = 0.3;  // the route keeps 0.45 m from every obstacle
  const pipeline::MapRun run = pipeline::MapSimulation(config, ToursFile("two_rings.yaml"),
                                                       ToursFile("two_rings_west.txt"), /*seed=*/1);
  const pipeline::TourEvaluation e = pipeline::EvaluateTour(run);
  std::printf("two_rings west ring: %s\n", pipeline::FormatTourEvaluation(e).c_str());
  ASSERT_GE(e.travel_m, 50.0);
  EXPECT_EQ(e.false_accepted, 0);
  EXPECT_GE(e.longest_loop_path_m, 45.0);  // the ring's closure itself was accepted
  EXPECT_LT(e.ate_m * 2.5, e.odometry_ate_m);
  EXPECT_LE(e.ate_m, 0.05);
  EXPECT_GE(e.wall_edges, 50);
  EXPECT_LE(e.wall_rejected * 10, e.wall_edges);
  EXPECT_LE(e.wall_error_rms_m, 0.02);
  EXPECT_LE(e.wall_error_max_m, 0.06);
  // The loops are accurate, and their information does not claim more than they deliver
  // (the translation error is a length: sqrt(2) per-axis sigmas).
  EXPECT_GT(e.loop_sigma_mean_m, 0.0);
  EXPECT_LE(e.loop_error_rms_m, 0.01);
  EXPECT_LE(e.loop_error_rms_yaw_rad, 1.0 * M_PI / 180);
  EXPECT_LE(e.loop_error_rms_m, std::sqrt(2.0) * e.loop_sigma_mean_m);
  EXPECT_LE(e.loop_error_rms_yaw_rad, e.loop_sigma_mean_yaw_rad);
}

}  // namespace
}  // namespace uwbsar
