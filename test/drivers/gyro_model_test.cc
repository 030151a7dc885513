// The simulated gyro (drivers/sim/gyro_model.h) and the odometry profiles built on it
// (drivers/sim/base_odometry.h): the heading error's statistics over many seeds match the
// configured noise, bias, bias walk and scale, and the kobuki_gyro profile takes its heading
// from the gyro while `wheel` is the wheel odometry unchanged.
#include "drivers/sim/gyro_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/config_io.h"
#include "drivers/sim/base_odometry.h"
#include "drivers/sim/route.h"
#include "drivers/sim/simulator_config.h"
#include "drivers/sim/trajectory.h"
#include "drivers/sim/wheel_odometry.h"

namespace uwbsar::sim {
namespace {

constexpr double kRadPerDeg = M_PI / 180.0;
constexpr double kRateHz = 50.0;  // the Kobuki's sensor data rate

SimGyroConfig QuietGyro() {
  SimGyroConfig c;
  c.rate_noise_density_dps_per_sqrt_hz = 0.0;
  c.turn_on_bias_std_dps = 0.0;
  c.bias_walk_dps_per_sqrt_s = 0.0;
  c.scale_error = 0.0;
  c.angle_resolution_deg = 0.0;
  return c;
}

/// Heading error of a gyro at standstill after each of `times_s` (ascending), for seeds
/// 1..num_seeds: errors[i][seed - 1].
std::vector<std::vector<double>> StandstillErrors(const SimGyroConfig& c,
                                                  const std::vector<double>& times_s, int num_seeds,
                                                  std::vector<double>* final_bias = nullptr) {
  std::vector<std::vector<double>> errors(times_s.size());
  for (int seed = 1; seed <= num_seeds; ++seed) {
    GyroModel gyro(c, 0.0, static_cast<std::uint64_t>(seed));
    int step = 0;
    for (std::size_t i = 0; i < times_s.size(); ++i) {
      double heading = 0.0;
      for (; step < static_cast<int>(std::lround(times_s[i] * kRateHz)); ++step) {
        heading = gyro.Step(1.0 / kRateHz, 0.0);
      }
      errors[i].push_back(heading);
    }
    if (final_bias) final_bias->push_back(gyro.bias_radps());
  }
  return errors;
}

double Mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double Rms(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

TEST(GyroModelTest, PerfectGyroIntegratesTheTrueTurn) {
  GyroModel gyro(QuietGyro(), 0.3, 1);
  double heading = 0.0;
  for (int i = 0; i < 500; ++i) heading = gyro.Step(0.02, 0.01);  // 0.5 rad/s for 10 s
  EXPECT_NEAR(heading, 0.3 + 5.0, 1e-9);
}

TEST(GyroModelTest, MeanRateErrorEqualsTheBias) {
  // White noise and a turn-on bias, no walk: over a long standstill the mean rate error is
  // the bias the run drew, to within the noise's standard error (N / sqrt(T)).
  SimGyroConfig c = QuietGyro();
  c.rate_noise_density_dps_per_sqrt_hz = 0.03;
  c.turn_on_bias_std_dps = 0.05;
  const double duration_s = 600.0;
  const double noise_se_radps = 0.03 * kRadPerDeg / std::sqrt(duration_s);
  std::vector<double> biases;
  for (int seed = 1; seed <= 20; ++seed) {
    GyroModel gyro(c, 0.0, static_cast<std::uint64_t>(seed));
    const double bias = gyro.bias_radps();
    double heading = 0.0;
    for (int i = 0; i < static_cast<int>(duration_s * kRateHz); ++i) {
      heading = gyro.Step(1.0 / kRateHz, 0.0);
    }
    EXPECT_NEAR(heading / duration_s, bias, 4.0 * noise_se_radps) << "seed " << seed;
    EXPECT_EQ(gyro.bias_radps(), bias);  // no walk configured
    biases.push_back(bias);
  }
  // The turn-on bias itself is drawn with the configured spread, over many runs.
  std::vector<double> many;
  for (int seed = 1; seed <= 4000; ++seed) {
    many.push_back(GyroModel(c, 0.0, static_cast<std::uint64_t>(seed)).bias_radps());
  }
  EXPECT_NEAR(Mean(many), 0.0, 4.0 * 0.05 * kRadPerDeg / std::sqrt(4000.0));
  EXPECT_NEAR(Rms(many) / (0.05 * kRadPerDeg), 1.0, 0.05);
}

TEST(GyroModelTest, HeadingRandomWalkGrowsAsTheSquareRootOfTime) {
  // White rate noise alone: the heading error after t has the standard deviation
  // N * sqrt(t), at every t (400 runs: the estimate's own spread is about 3.5 %).
  SimGyroConfig c = QuietGyro();
  c.rate_noise_density_dps_per_sqrt_hz = 0.03;
  const std::vector<double> times_s = {25.0, 100.0, 400.0};
  const auto errors = StandstillErrors(c, times_s, 400);
  for (std::size_t i = 0; i < times_s.size(); ++i) {
    const double expected = 0.03 * kRadPerDeg * std::sqrt(times_s[i]);
    EXPECT_NEAR(Rms(errors[i]) / expected, 1.0, 0.12) << times_s[i] << " s";
    EXPECT_NEAR(Mean(errors[i]), 0.0, 4.0 * expected / std::sqrt(400.0));
  }
  // Doubling per quadrupled time, not linear growth.
  EXPECT_NEAR(Rms(errors[2]) / Rms(errors[1]), 2.0, 0.25);
  EXPECT_NEAR(Rms(errors[1]) / Rms(errors[0]), 2.0, 0.25);
}

TEST(GyroModelTest, BiasWalksAsTheSquareRootOfTime) {
  // The bias walk alone: the bias after t has the spread K * sqrt(t), and the heading error it
  // integrates K * t^1.5 / sqrt(3).
  SimGyroConfig c = QuietGyro();
  c.bias_walk_dps_per_sqrt_s = 0.002;
  const double t = 300.0;
  std::vector<double> bias;
  const auto errors = StandstillErrors(c, {t}, 400, &bias);
  const double k = 0.002 * kRadPerDeg;
  EXPECT_NEAR(Rms(bias) / (k * std::sqrt(t)), 1.0, 0.12);
  EXPECT_NEAR(Rms(errors[0]) / (k * std::pow(t, 1.5) / std::sqrt(3.0)), 1.0, 0.12);
}

TEST(GyroModelTest, ScaleErrorScalesTurns) {
  SimGyroConfig c = QuietGyro();
  c.scale_error = 0.01;
  GyroModel gyro(c, 0.0, 1);
  double heading = 0.0;
  for (int i = 0; i < 1000; ++i) heading = gyro.Step(0.02, 0.01);  // 10 rad at 0.5 rad/s
  EXPECT_NEAR(heading, 10.0 * 1.01, 1e-9);
}

TEST(GyroModelTest, RatesBeyondTheRangeSaturate) {
  SimGyroConfig c = QuietGyro();  // range 110 deg/s
  GyroModel gyro(c, 0.0, 1);
  double heading = 0.0;
  for (int i = 0; i < 50; ++i) heading = gyro.Step(0.02, 3.0 * 0.02);  // 1 s at 3 rad/s
  EXPECT_NEAR(heading, 110.0 * kRadPerDeg, 1e-9);
  GyroModel slow(c, 0.0, 1);
  for (int i = 0; i < 50; ++i) heading = slow.Step(0.02, 1.5 * 0.02);  // 86 deg/s: in range
  EXPECT_NEAR(heading, 1.5, 1e-9);
}

TEST(GyroModelTest, HeadingIsReportedInStepsOfTheResolution) {
  SimGyroConfig c = QuietGyro();
  c.angle_resolution_deg = 0.01;
  c.rate_noise_density_dps_per_sqrt_hz = 0.03;
  const double start = 0.1234;
  GyroModel gyro(c, start, 3);
  const double step_rad = 0.01 * kRadPerDeg;
  for (int i = 0; i < 200; ++i) {
    const double heading = gyro.Step(0.02, 0.0037);
    const double steps = (heading - start) / step_rad;
    ASSERT_NEAR(steps, std::round(steps), 1e-6);
    ASSERT_LE(std::abs(heading - gyro.heading_rad()), 0.5 * step_rad + 1e-12);
  }
}

TEST(GyroModelTest, SameSeedSameHeadingsOtherSeedOthers) {
  const SimGyroConfig c;  // the Kobuki defaults
  GyroModel a(c, 0.0, 5), b(c, 0.0, 5), other(c, 0.0, 6);
  bool differs = false;
  for (int i = 0; i < 500; ++i) {
    const double ha = a.Step(0.02, 0.004);
    ASSERT_EQ(ha, b.Step(0.02, 0.004));
    differs = differs || ha != other.Step(0.02, 0.004);
  }
  EXPECT_TRUE(differs);
}

TEST(GyroModelTest, TurnOnBiasFixedInSigmasIsThatManySigmasOnEverySeed) {
  // simulator.odometry.gyro.turn_on_bias_sigmas: k fixes the turn-on bias at exactly k times
  // turn_on_bias_std_dps whatever the seed (the noise and the walk still come from it); null, the
  // default, draws it from the seed.
  const SimulatorConfig plus = ReadConfigYaml<SimulatorConfig>(
      "odometry:\n  gyro:\n    turn_on_bias_sigmas: 3\n", "plus.yaml");
  const SimulatorConfig minus = ReadConfigYaml<SimulatorConfig>(
      "odometry:\n  gyro:\n    turn_on_bias_sigmas: -3.0\n", "minus.yaml");
  const SimulatorConfig drawn = ReadConfigYaml<SimulatorConfig>(
      "odometry:\n  gyro:\n    turn_on_bias_sigmas: null\n", "drawn.yaml");
  EXPECT_NO_THROW(Validate(plus, "plus.yaml"));
  EXPECT_FALSE(drawn.odometry.gyro.turn_on_bias_sigmas.has_value());
  const double sigma_radps = SimGyroConfig{}.turn_on_bias_std_dps * kRadPerDeg;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    GyroModel p(plus.odometry.gyro, 0.0, seed), m(minus.odometry.gyro, 0.0, seed);
    GyroModel d(drawn.odometry.gyro, 0.0, seed), default_gyro(SimGyroConfig{}, 0.0, seed);
    EXPECT_EQ(p.bias_radps(), 3.0 * sigma_radps) << seed;
    EXPECT_EQ(m.bias_radps(), -3.0 * sigma_radps) << seed;
    EXPECT_EQ(d.bias_radps(), default_gyro.bias_radps()) << seed;
    // The same noise and walk as the drawn run: the headings differ by the biases' difference.
    const double offset_radps = p.bias_radps() - d.bias_radps();
    for (int i = 1; i <= 100; ++i) {
      p.Step(0.02, 0.001);
      d.Step(0.02, 0.001);
      ASSERT_NEAR(p.heading_rad() - d.heading_rad(), offset_radps * 0.02 * i, 1e-12) << seed;
    }
  }
  // More than 10 sigmas is no turn-on bias a gyro has: refused, naming the key.
  SimulatorConfig far = plus;
  far.odometry.gyro.turn_on_bias_sigmas = 11.0;
  try {
    Validate(far, "far.yaml");
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("simulator.odometry.gyro.turn_on_bias_sigmas"),
              std::string::npos)
        << e.what();
  }
}

// --- Profiles ---

std::vector<OdometrySample> Drive(const Trajectory& t, const SimOdometryConfig& c,
                                  std::uint64_t seed) {
  BaseOdometrySimulator odom(c, t.At(0.0), seed, seed + 100);
  std::vector<OdometrySample> out;
  const int n = static_cast<int>(std::floor(t.duration_s() * c.rate_hz));
  for (int i = 0; i <= n; ++i)
    out.push_back(odom.Step(SecondsToNs(i / c.rate_hz), t.At(i / c.rate_hz)));
  return out;
}

SimOdometryConfig PerfectWheels(const std::string& profile) {
  SimOdometryConfig c;
  c.profile = profile;
  c.wheel_scale_error = c.wheel_scale_asymmetry = c.wheelbase_error = c.wheel_slip_std = 0.0;
  c.gyro = QuietGyro();
  return c;
}

TEST(OdometryProfileTest, WheelProfileIsTheWheelOdometryExactly) {
  const SimRouteConfig rc;
  const Trajectory t = Trajectory::Plan(BuiltInRoute("loop", rc), rc);
  SimOdometryConfig c;  // the default wheel errors and slip
  c.profile = "wheel";
  const std::vector<OdometrySample> base = Drive(t, c, 9);
  WheelOdometrySimulator wheels(c, t.At(0.0), 9);
  for (std::size_t i = 0; i < base.size(); ++i) {
    const double s = static_cast<double>(i) / c.rate_hz;
    const OdometrySample w = wheels.Step(SecondsToNs(s), t.At(s));
    ASSERT_EQ(w.T_world_robot.x_m, base[i].T_world_robot.x_m) << i;
    ASSERT_EQ(w.T_world_robot.y_m, base[i].T_world_robot.y_m) << i;
    ASSERT_EQ(w.T_world_robot.yaw_rad, base[i].T_world_robot.yaw_rad) << i;
    ASSERT_EQ(w.angular_velocity_radps, base[i].angular_velocity_radps) << i;
  }
}

TEST(OdometryProfileTest, KobukiGyroProfileTakesTheHeadingFromTheGyro) {
  // Wheels that under-report turns by 2 % (wheelbase error) and drift sideways (asymmetry):
  // with a perfect gyro the heading is exact, and the pose error is the wheels' distance
  // alone; wheel-only odometry keeps the heading error.
  const SimRouteConfig rc;
  const Trajectory t = Trajectory::Plan(BuiltInRoute("depart-return", rc), rc);
  SimOdometryConfig gyro = PerfectWheels("kobuki_gyro");
  gyro.wheelbase_error = 0.02;
  gyro.wheel_scale_asymmetry = 0.01;
  SimOdometryConfig wheel = gyro;
  wheel.profile = "wheel";
  const Pose2 truth = t.At(std::floor(t.duration_s() * gyro.rate_hz) / gyro.rate_hz).T_world_robot;
  const Pose2 by_gyro = Drive(t, gyro, 1).back().T_world_robot;
  const Pose2 by_wheel = Drive(t, wheel, 1).back().T_world_robot;
  EXPECT_LT(std::abs(NormalizeAngle(by_gyro.yaw_rad - truth.yaw_rad)), 1e-6);
  EXPECT_LT(Distance(by_gyro, truth), 0.01);
  EXPECT_GT(std::abs(NormalizeAngle(by_wheel.yaw_rad - truth.yaw_rad)), 0.05);
  EXPECT_GT(Distance(by_wheel, truth), 0.1);
}

TEST(OdometryProfileTest, KobukiGyroProfileKeepsTheWheelsDistanceScale) {
  SimRouteConfig rc;
  const Route straight{"straight", {{0, 0}, {10, 0}}};
  SimOdometryConfig c = PerfectWheels("kobuki_gyro");
  c.wheel_scale_error = 0.02;
  const Pose2 end = Drive(Trajectory::Plan(straight, rc), c, 1).back().T_world_robot;
  EXPECT_NEAR(end.x_m, 10.2, 0.002);
  EXPECT_NEAR(end.y_m, 0.0, 1e-3);
}

TEST(OdometryProfileTest, KobukiGyroHeadingErrorFollowsTheGyroNotTheWheels) {
  // Default wheels (slip, asymmetry, wheelbase error) under the default gyro: the heading
  // error at the end equals the gyro's own (wheels play no part in it).
  const SimRouteConfig rc;
  const Trajectory t = Trajectory::Plan(BuiltInRoute("loop", rc), rc);
  SimOdometryConfig c;
  ASSERT_EQ(c.profile, "kobuki_gyro");  // the default
  BaseOdometrySimulator odom(c, t.At(0.0), 4, 40);
  const int n = static_cast<int>(std::floor(t.duration_s() * c.rate_hz));
  OdometrySample last;
  for (int i = 0; i <= n; ++i) last = odom.Step(SecondsToNs(i / c.rate_hz), t.At(i / c.rate_hz));
  ASSERT_NE(odom.gyro(), nullptr);
  const RobotState truth = t.At(n / c.rate_hz);
  const double gyro_error =
      odom.gyro()->heading_rad() - truth.heading_rad - t.At(0.0).T_world_robot.yaw_rad;
  EXPECT_NEAR(NormalizeAngle(last.T_world_robot.yaw_rad - truth.T_world_robot.yaw_rad), gyro_error,
              0.5 * 0.01 * kRadPerDeg + 1e-9);
}

TEST(OdometryProfileTest, UnknownProfileIsRefusedNamingTheKey) {
  SimulatorConfig c;
  c.odometry.profile = "gyro";
  try {
    Validate(c, "robot.yaml");
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("robot.yaml"), std::string::npos) << msg;
    EXPECT_NE(msg.find("simulator.odometry.profile"), std::string::npos) << msg;
    EXPECT_NE(msg.find("kobuki_gyro or wheel"), std::string::npos) << msg;
  }
  c.odometry.profile = "wheel";
  EXPECT_NO_THROW(Validate(c, "robot.yaml"));
  c.odometry.gyro.rate_noise_density_dps_per_sqrt_hz = -1.0;
  EXPECT_THROW(Validate(c, "robot.yaml"), ConfigError);
}

}  // namespace
}  // namespace uwbsar::sim
