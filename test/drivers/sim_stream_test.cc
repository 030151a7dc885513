// The simulated recording: message order and rates, determinism, outputs (TUM,
// text log, ROS 2 bag read back with the project's reader), scenario errors.
#include "drivers/sim/sim_stream.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/app_config_io.h"
#include "drivers/rosbag/robot_bag.h"
#include "drivers/sim/sim_bag_writer.h"
#include "drivers/sim/sim_recorder.h"
#include "test/drivers/sim_test_util.h"
#include "test/shared_data.h"

namespace uwbsar::sim {
namespace {

namespace fs = std::filesystem;

/// A short seed_lab run: 1.5 m out and back, fast, radar and ground truth at low rates.
Config ShortRunConfig() {
  Config c;
  c.simulator.radar.rate_hz = 25.0;
  c.simulator.odometry.ground_truth_rate_hz = 50.0;
  c.simulator.route.depart_distance_m = 1.5;
  c.simulator.route.speed_mps = 0.5;
  c.simulator.route.accel_mps2 = 1.0;
  c.simulator.route.turn_rate_radps = 2.0;
  c.simulator.route.turn_accel_radps2 = 4.0;
  c.simulator.route.pause_s = 0.2;
  return c;
}

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("uwbsar_simstream_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SimStreamTest, MessagesAreTimeOrderedAtTheirRates) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const Config config = ShortRunConfig();
  const SimScenario scenario = MakeScenario(config, testing::SeedLabMap(), "depart-return", 1);
  SimStream stream(config, scenario, 1);
  const double duration = stream.duration_s();
  EXPECT_GE(duration, scenario.trajectory.duration_s());
  EXPECT_LT(duration, scenario.trajectory.duration_s() + 1.0 / config.simulator.odometry.rate_hz);
  SimMessage msg;
  TimestampNs last = 0;
  long long counts[4] = {0, 0, 0, 0};
  long long per_radar[2] = {0, 0};
  while (stream.Next(&msg)) {
    EXPECT_GE(msg.stamp_ns, last);
    last = msg.stamp_ns;
    ++counts[static_cast<int>(msg.kind)];
    if (msg.kind == SimMessage::Kind::kRadarScan) {
      ++per_radar[msg.scan.sensor_id];
      ASSERT_EQ(msg.scan.samples.size(), 1000u);
      EXPECT_EQ(msg.scan.stamp_ns, msg.stamp_ns);
    }
  }
  auto expected = [&](double rate) { return static_cast<long long>(duration * rate + 1e-9) + 1; };
  const SimulatorConfig& sc = config.simulator;
  EXPECT_EQ(counts[0], expected(sc.odometry.ground_truth_rate_hz));
  EXPECT_EQ(counts[1], expected(sc.odometry.rate_hz));
  EXPECT_EQ(per_radar[0], expected(sc.radar.rate_hz));
  EXPECT_EQ(per_radar[1], per_radar[0]);
  EXPECT_EQ(counts[3], 0);  // laser off by default
  EXPECT_EQ(stream.start_ns(), SecondsToNs(config.simulator.start_time_s));
  EXPECT_NEAR(NsToSeconds(last - stream.start_ns()), duration, 1e-6);
}

TEST(SimStreamTest, ScansSeeTheRoomWallsAtTheirRange) {
  UWBSAR_NEED_SEED_LAB_MAP();
  // At the start (0, 0) the left radar (y = +0.18 m) faces the wall at y = 1.6 m and the
  // right radar the one at y = -1.8 m: both walls are lit straight ahead, and each scan's
  // leading edge sits at the range of its nearest lit scatterer (less half a pulse).
  Config config = ShortRunConfig();
  config.simulator.radar.noise_std = 0.0;
  config.simulator.radar.coupling_amplitude = 0.0;
  const SimScenario scenario = MakeScenario(config, testing::SeedLabMap(), "depart-return", 1);
  const SimEnvironment& env = *scenario.environment;
  const OccupancyGrid& grid = env.grid();
  SimStream stream(config, scenario, 1);
  SimMessage msg;
  const double bin = 299792458.0 / (2 * 23.328e9);
  const Point2 antenna[2] = {{0.0, 0.18}, {0.0, -0.18}};
  const double wall_y[2] = {1.6, -1.8};
  int seen = 0;
  while (seen < 2 && stream.Next(&msg)) {
    if (msg.kind != SimMessage::Kind::kRadarScan) continue;
    const int k = msg.scan.sensor_id;
    ++seen;
    int row = 0, col = 0;
    ASSERT_TRUE(grid.CellOf({0.0, wall_y[k]}, &row, &col));
    const std::vector<int>& lit = stream.lit_cells(k);
    EXPECT_NE(std::find(lit.begin(), lit.end(), row * grid.cols + col), lit.end()) << k;
    double nearest = 1e9;
    for (int cell : lit) {
      for (int i = env.CellBegin(cell); i < env.CellEnd(cell); ++i) {
        const SimScatterer& sc = env.scatterers()[i];
        nearest = std::min(nearest, std::hypot(sc.x_m - antenna[k].x_m, sc.y_m - antenna[k].y_m));
      }
    }
    EXPECT_LT(nearest, std::abs(wall_y[k] - antenna[k].y_m) + 0.05);
    int first = 0;
    while (first < 1000 && std::abs(msg.scan.samples[first]) < 1e-5) ++first;
    // The pulse envelope is above 1e-5 out to ~0.14 m from its centre for these echoes.
    EXPECT_NEAR(first * bin, nearest - 0.14, 0.05) << "radar " << k;
  }
  EXPECT_EQ(seen, 2);
}

TEST(SimStreamTest, SameSeedSameMessagesOtherSeedOtherNoise) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const Config config = ShortRunConfig();
  const SimScenario a_scenario = MakeScenario(config, testing::SeedLabMap(), "depart-return", 3);
  const SimScenario c_scenario = MakeScenario(config, testing::SeedLabMap(), "depart-return", 4);
  SimStream a(config, a_scenario, 3), b(config, a_scenario, 3), c(config, c_scenario, 4);
  const SimRecording ra = RecordStream(&a), rb = RecordStream(&b), rc = RecordStream(&c);
  ASSERT_EQ(ra.scans.size(), rb.scans.size());
  for (std::size_t i = 0; i < ra.scans.size(); ++i) {
    ASSERT_EQ(ra.scans[i].samples, rb.scans[i].samples) << i;
  }
  for (std::size_t i = 0; i < ra.odometry.size(); ++i) {
    ASSERT_EQ(ra.odometry[i].T_world_robot.x_m, rb.odometry[i].T_world_robot.x_m);
  }
  EXPECT_NE(ra.scans[10].samples, rc.scans[10].samples);
  EXPECT_NE(ra.odometry.back().T_world_robot.x_m, rc.odometry.back().T_world_robot.x_m);
}

TEST(SimStreamTest, OdometryAndTruthStartTogetherAndDrift) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config = ShortRunConfig();
  config.simulator.odometry.wheel_scale_error = 0.05;
  const SimScenario scenario = MakeScenario(config, testing::SeedLabMap(), "depart-return", 1);
  SimStream stream(config, scenario, 1);
  const SimRecording rec = RecordStream(&stream);
  EXPECT_EQ(Distance(rec.odometry.front().T_world_robot, rec.ground_truth.front().T_world_robot),
            0.0);
  // Halfway (at the far end) the odometry overshoots by about 5 % of 1.5 m.
  double max_x = 0.0;
  for (const OdometrySample& o : rec.odometry) max_x = std::max(max_x, o.T_world_robot.x_m);
  EXPECT_NEAR(max_x, 1.5 * 1.05, 0.01);
}

TEST(SimStreamTest, TrueGyroBiasIsTheBiasTheRunsOdometryIntegrated) {
  // A gyro whose only error is its bias (fixed turn-on, a fast walk): each odometry step's
  // heading error is the mean of the replayed biases at its ends times the step.
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config = ShortRunConfig();
  SimGyroConfig& g = config.simulator.odometry.gyro;
  g.rate_noise_density_dps_per_sqrt_hz = g.scale_error = g.angle_resolution_deg = 0.0;
  g.bias_walk_dps_per_sqrt_s = 0.05;
  g.turn_on_bias_sigmas = 3.0;
  g.range_dps = 1000.0;
  config.simulator.odometry.ground_truth_rate_hz = config.simulator.odometry.rate_hz;
  const SimScenario scenario = MakeScenario(config, testing::SeedLabMap(), "depart-return", 2);
  SimStream stream(config, scenario, 2);
  const SimRecording rec = RecordStream(&stream);
  ASSERT_EQ(rec.odometry.size(), rec.ground_truth.size());
  std::vector<double> times_s;
  for (const OdometrySample& o : rec.odometry) {
    times_s.push_back(NsToSeconds(o.stamp_ns - rec.odometry.front().stamp_ns));
  }
  const std::vector<double> bias = TrueGyroBiasRadps(config.simulator.odometry, 2, times_s);
  ASSERT_EQ(bias.size(), times_s.size());
  EXPECT_DOUBLE_EQ(bias.front(), 3.0 * g.turn_on_bias_std_dps * M_PI / 180.0);
  EXPECT_NE(bias.back(), bias.front());  // it walked
  auto error = [&rec](std::size_t i) {
    return NormalizeAngle(rec.odometry[i].T_world_robot.yaw_rad -
                          rec.ground_truth[i].T_world_robot.yaw_rad);
  };
  for (std::size_t i = 1; i < rec.odometry.size(); ++i) {
    ASSERT_EQ(rec.odometry[i].stamp_ns, rec.ground_truth[i].stamp_ns);
    const double dt = times_s[i] - times_s[i - 1];
    ASSERT_NEAR(NormalizeAngle(error(i) - error(i - 1)), 0.5 * (bias[i - 1] + bias[i]) * dt, 1e-9)
        << i;
  }
}

TEST(SimStreamTest, LaserMeasuresTheWallsWhenEnabled) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config = ShortRunConfig();
  config.simulator.laser.enabled = true;
  config.simulator.laser.noise_std_m = 0.0;
  const SimScenario scenario = MakeScenario(config, testing::SeedLabMap(), "depart-return", 1);
  SimStream stream(config, scenario, 1);
  const SimRecording rec = RecordStream(&stream);
  ASSERT_FALSE(rec.laser.empty());
  const SimLaserScan& first = rec.laser.front();
  ASSERT_EQ(first.ranges_m.size(), 360u);
  // Beam 270 points to +90 deg (left): the wall at y = 1.6 m; beam 90 to the right wall.
  EXPECT_NEAR(first.ranges_m[270], 1.6, 0.06);
  EXPECT_NEAR(first.ranges_m[90], 1.8, 0.06);
}

TEST(SimRecorderTest, TumLinesHoldExactStampsAndQuaternions) {
  OdometrySample p;
  p.stamp_ns = 1'700'000'000'005'000'001;
  p.T_world_robot = {1.5, -2.25, M_PI / 2};
  EXPECT_EQ(TumLine(p), "1700000000.005000001 1.500000 -2.250000 0 0 0 0.707106781 0.707106781");
}

TEST(SimRecorderTest, TextLogAndTumAreWrittenAndReadBack) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const Config config = ShortRunConfig();
  const SimScenario scenario = MakeScenario(config, testing::SeedLabMap(), "depart-return", 1);
  SimStream stream(config, scenario, 1);
  const SimRecording rec = RecordStream(&stream);
  const fs::path dir = TempDir("textlog");
  WriteTextLog((dir / "log.txt").string(), ToTextLog(rec));
  WriteTumTrajectory((dir / "gt.tum").string(), rec.ground_truth);
  const TextLog back = ReadTextLog((dir / "log.txt").string());
  ASSERT_EQ(back.scans.size(), rec.scans.size());
  ASSERT_EQ(back.odometry.size(), rec.odometry.size());
  EXPECT_NEAR(back.scans[7].samples[300], rec.scans[7].samples[300], 1e-6);
  std::ifstream tum(dir / "gt.tum");
  std::string line;
  int lines = 0;
  while (std::getline(tum, line)) lines += !line.empty() && line[0] != '#';
  EXPECT_EQ(lines, static_cast<int>(rec.ground_truth.size()));
  fs::remove_all(dir);
}

TEST(SimBagTest, BagReadsBackAsTheStreamAndIsReproducible) {
  UWBSAR_NEED_SEED_LAB_MAP();
  for (const std::string storage : {"sqlite3", "mcap"}) {
    Config config = ShortRunConfig();
    config.simulator.laser.enabled = true;
    const SimScenario scenario = MakeScenario(config, testing::SeedLabMap(), "depart-return", 2);
    const fs::path dir = TempDir("bag_" + storage);
    SimStream stream(config, scenario, 2);
    // Two bags of the same name in different folders, to compare byte for byte.
    fs::create_directories(dir / "a");
    fs::create_directories(dir / "b");
    const SimBagSummary summary = WriteSimBag(&stream, config, (dir / "a" / "sim").string(),
                                              storage, (dir / "a.tum").string());
    SimStream again(config, scenario, 2);
    WriteSimBag(&again, config, (dir / "b" / "sim").string(), storage, "");
    SimStream memory_stream(config, scenario, 2);
    const SimRecording rec = RecordStream(&memory_stream);

    const rosbag::RobotLog log = rosbag::LoadRobotBag((dir / "a" / "sim").string(),
                                                      rosbag::RobotBagOptionsFromConfig(config));
    ASSERT_EQ(log.scans.size(), rec.scans.size()) << storage;
    EXPECT_EQ(static_cast<long long>(log.scans.size()), summary.radar_scans);
    for (std::size_t i = 0; i < rec.scans.size(); i += 37) {
      EXPECT_EQ(log.scans[i].samples, rec.scans[i].samples);
      EXPECT_EQ(log.scans[i].sensor_id, rec.scans[i].sensor_id);
      EXPECT_EQ(log.scans[i].stamp_ns, rec.scans[i].stamp_ns);
    }
    ASSERT_EQ(log.odometry.size(), rec.odometry.size());
    ASSERT_EQ(log.ground_truth.size(), rec.ground_truth.size());
    const Pose2& o = log.odometry.back().T_world_robot;
    EXPECT_NEAR(o.x_m, rec.odometry.back().T_world_robot.x_m, 1e-12);
    EXPECT_NEAR(o.yaw_rad, rec.odometry.back().T_world_robot.yaw_rad, 1e-12);
    EXPECT_EQ(log.stats.laser_scans, rec.laser.size());
    // Same seed, same bytes: every file of both bags is identical.
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir / "a" / "sim")) {
      const fs::path other = dir / "b" / "sim" / entry.path().filename();
      ++files;
      ASSERT_TRUE(fs::exists(other)) << other;
      EXPECT_EQ(ReadFile(entry.path()), ReadFile(other)) << entry.path();
    }
    EXPECT_EQ(files, 2);  // metadata.yaml and the storage file
    EXPECT_TRUE(fs::exists(dir / "a.tum"));
    // An existing bag is never overwritten.
    SimStream third(config, scenario, 2);
    EXPECT_THROW(WriteSimBag(&third, config, (dir / "a" / "sim").string(), storage, ""),
                 InputError);
    fs::remove_all(dir);
  }
}

TEST(SimScenarioTest, BadRouteOrMapIsAnInputError) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const Config config = ShortRunConfig();
  EXPECT_THROW(MakeScenario(config, testing::SeedLabMap(), "spiral", 1), InputError);
  EXPECT_THROW(MakeScenario(config, "/nonexistent/map.yaml", "loop", 1), InputError);
  Config far = config;
  far.simulator.route.depart_distance_m = 15.0;  // through the room's end wall
  EXPECT_THROW(MakeScenario(far, testing::SeedLabMap(), "depart-return", 1), InputError);
  // The paper's run and the loop fit the room.
  EXPECT_NO_THROW(MakeScenario(Config{}, testing::SeedLabMap(), "depart-return", 1));
  EXPECT_NO_THROW(MakeScenario(Config{}, testing::SeedLabMap(), "loop", 1));
}

TEST(SimScenarioTest, PointTargetsComeFromConfigAndFile) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const fs::path dir = TempDir("targets");
  std::ofstream(dir / "poles.yaml") << "point_targets:\n  - {x_m: 2.0, y_m: 1.0, rcs_m2: 0.5}\n"
                                       "  - {x_m: 4.0, y_m: -1.0}\n";
  const std::vector<PointTargetConfig> targets = LoadPointTargets((dir / "poles.yaml").string());
  ASSERT_EQ(targets.size(), 2u);
  EXPECT_DOUBLE_EQ(targets[1].rcs_m2, PointTargetConfig{}.rcs_m2);
  Config config = ShortRunConfig();
  config.simulator.radar.point_targets = {{3.0, 1.2, 1.0}};
  const SimScenario s = MakeScenario(config, testing::SeedLabMap(), "loop", 1, targets);
  EXPECT_EQ(s.environment->point_targets().size(), 3u);
  std::ofstream(dir / "bad.yaml") << "point_targets:\n  - {x_m: 2.0, z_m: 1.0}\n";
  try {
    LoadPointTargets((dir / "bad.yaml").string());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("z_m"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(SimConfigTest, InvalidSimulatorSettingsAreRejected) {
  EXPECT_THROW(LoadConfigFromString("simulator:\n  radar:\n    rate_hz: 0\n", "s.yaml"),
               ConfigError);
  EXPECT_THROW(LoadConfigFromString("simulator:\n  route:\n    speed_mps: -1\n", "s.yaml"),
               ConfigError);
  EXPECT_THROW(LoadConfigFromString("simulator:\n  odometry:\n    wheel_slip_std: 2\n", "s.yaml"),
               ConfigError);
  EXPECT_THROW(LoadConfigFromString("simulator:\n  laser:\n    max_range_m: 0.1\n", "s.yaml"),
               ConfigError);
  const Config ok = LoadConfigFromString(
      "simulator:\n  radar:\n    point_targets:\n      - {x_m: 1, y_m: 2, rcs_m2: 0.3}\n",
      "s.yaml");
  ASSERT_EQ(ok.simulator.radar.point_targets.size(), 1u);
  EXPECT_DOUBLE_EQ(ok.simulator.radar.point_targets[0].rcs_m2, 0.3);
}

}  // namespace
}  // namespace uwbsar::sim
