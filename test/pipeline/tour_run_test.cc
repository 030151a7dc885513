// A ring closed only after 50 m on a generated building floor
// (config/maps/tours/two_rings.yaml, the west ring of the figure of eight, 55 m), mapped
// with the default configuration: the ring's closure itself is accepted (a loop between
// the tour's start and its end), no false loop, SLAM beats odometry alone. Measured (seed
// 1): 9 loops, ATE 6.24 cm against 12.34 cm of odometry (2.0x; 6.49 cm before the online
// odometry calibration): the 5 cm / 3x goal is not met here. What is left is the
// odometry's systematic error, which one ring closure cannot separate: around a ring the
// heading drift per metre and the turns' scale error move the closure alike, and the
// distance scale not at all (with the simulator's true intrinsics held fixed the same run
// gives 1.85 cm; README "Measured"). The full set of tours and seeds is
// `uwbsar_bench --benchmark_filter=Tour`.
#include <gtest/gtest.h>

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
  EXPECT_LT(e.ate_m * 1.5, e.odometry_ate_m);
  EXPECT_LE(e.ate_m, 0.08);
}

}  // namespace
}  // namespace uwbsar
