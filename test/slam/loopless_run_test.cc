// Runs that find no loop (issue 32, point 0: never worse than odometry without evidence).
// Before the first accepted loop the odometry calibration stays at its prior: wall edges alone
// see the heading drift on straight stretches but never the turns' scale, and correcting one of
// the two heading errors where they cancel over a lap moved the path away from the truth
// (backend/pose_graph_calibration.cc, UpdateCalibrationFreedom).
//  - One lap of the office ring (config/maps/office, seed 3) whose end only brushes its start:
//    before, the wall edges freed the calibration, whose drift went to 0.0007 rad/m (truth
//    0.003) with the turns' scale left at 0, and the ATE rose from 9.93 cm (odometry) to
//    12.84 cm; held at the prior, 10.42 cm. The rest is the wall edges themselves: they
//    straighten each stretch (the drift's part of the heading error) while the turns' part
//    stays, at any weight (lateral_std_m 0.1: 10.27 cm); hence the 6 % allowed over odometry.
//  - A straight corridor (hall_wing's south corridor, 26 m, seed 3): its two walls become two
//    landmarks (place_recognition.wall_profiles.landmarks) that straighten it; ATE 3.88 cm
//    against 5.75 cm of odometry (the wall edges alone: 4.15 cm).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "backend/odometry_calibration.h"
#include "eval/tour/tour_eval.h"
#include "slam/app_config.h"
#include "slam/map_job.h"
#include "slam/slam_system.h"

namespace uwbsar {
namespace {

std::string MapsFile(const std::string& name) {
  return std::string(UWBSAR_SOURCE_DIR) + "/config/maps/" + name;
}

/// A route file (x_m y_m per line) in the test's temporary folder.
std::string WriteRoute(const std::string& name, const std::string& waypoints) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << waypoints;
  return path;
}

eval::TourEvaluation MapLooplessRun(const std::string& label, const std::string& map_yaml,
                                    const std::string& route, OdometryCalibration* calibration,
                                    bool wall_landmarks = true) {
  Config config;
  config.place_recognition.wall_profiles.landmarks.enabled = wall_landmarks;
  // These runs are uncalibrated; the landmarks are asked for explicitly.
  config.place_recognition.wall_profiles.landmarks.require_calibrated_base = false;
  config.simulator.route.clearance_m = 0.3;  // both routes keep 0.45 m from every obstacle
  const slam::MapRun run = slam::MapSimulation(config, map_yaml, route, /*seed=*/3);
  const eval::TourEvaluation e = eval::EvaluateTour(run);
  *calibration = run.slam->graph().OdometryCalibrations().at(0);
  std::printf("%s: %s\ncalibration: scale %.5f, drift %.6f rad/m, rotation %.5f\n", label.c_str(),
              eval::FormatTourEvaluation(e).c_str(), (*calibration)[kCalibScale],
              (*calibration)[kCalibHeadingDrift], (*calibration)[kCalibRotation]);
  return e;
}

TEST(LooplessRunTest, OfficeRingOneLapKeepsTheCalibrationAtItsPriorAndStaysNearTheOdometry) {
  OdometryCalibration calibration{};
  const eval::TourEvaluation e = MapLooplessRun(
      "office ring, one lap", MapsFile("office/office.yaml"),
      WriteRoute("office_one_lap.txt", "14 9\n4 9\n4 4\n16 4\n16 9\n14 9\n"), &calibration);
  ASSERT_GE(e.travel_m, 30.0);
  ASSERT_EQ(e.accepted, 0);  // the end only brushes the start: no loop
  EXPECT_GE(e.wall_edges + e.landmark_observations, 10);
  EXPECT_EQ(calibration, (OdometryCalibration{0.0, 0.0, 0.0}));  // the prior's mean
  EXPECT_LE(e.ate_m, 1.06 * e.odometry_ate_m);
}

TEST(LooplessRunTest, StraightCorridorIsNoWorseThanOdometry) {
  OdometryCalibration calibration{};
  const eval::TourEvaluation e =
      MapLooplessRun("hall_wing corridor", MapsFile("tours/hall_wing.yaml"),
                     WriteRoute("corridor.txt", "11 5\n37 5\n"), &calibration);
  ASSERT_GE(e.travel_m, 25.0);
  ASSERT_EQ(e.accepted, 0);
  EXPECT_GE(e.landmarks, 2);               // the corridor's two walls ...
  EXPECT_GE(e.landmark_observations, 30);  // ... seen along most of its 26 keyframes
  EXPECT_EQ(e.landmark_rejected, 0);
  EXPECT_LT(e.landmark_error_max_m, 0.03);  // every observation on its wall's line
  EXPECT_EQ(calibration, (OdometryCalibration{0.0, 0.0, 0.0}));
  EXPECT_LE(e.ate_m, e.odometry_ate_m);
}

// The wall edges alone (place_recognition.wall_profiles.landmarks.enabled false): the
// corridor is no worse than its odometry either (4.15 cm against 5.75 cm; with the landmarks,
// the default, 3.88 cm).
TEST(LooplessRunTest, StraightCorridorWithWallEdgesAloneIsNoWorseThanOdometry) {
  OdometryCalibration calibration{};
  const eval::TourEvaluation e =
      MapLooplessRun("hall_wing corridor, wall edges alone", MapsFile("tours/hall_wing.yaml"),
                     WriteRoute("corridor_edges.txt", "11 5\n37 5\n"), &calibration, false);
  ASSERT_EQ(e.accepted, 0);
  EXPECT_GE(e.wall_edges, 30);
  EXPECT_EQ(e.landmarks, 0);
  EXPECT_EQ(calibration, (OdometryCalibration{0.0, 0.0, 0.0}));
  EXPECT_LE(e.ate_m, e.odometry_ate_m);
}

}  // namespace
}  // namespace uwbsar
