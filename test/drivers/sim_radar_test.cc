// The radar signal model: delay 2R/c, 1/R^2, beam pattern, occlusion, coupling, noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "drivers/sim/radar_simulator.h"
#include "imaging/pulse.h"
#include "test/drivers/sim_test_util.h"

namespace uwbsar::sim {
namespace {

using testing::FreeGrid;
using testing::WallAlongX;

/// A quiet radar (no coupling, no noise) looking along +x from the origin.
struct Rig {
  PulseConfig pulse;
  SimRadarConfig radar;
  SensorGeometry sensor;

  Rig() {
    radar.coupling_amplitude = 0.0;
    radar.noise_std = 0.0;
    RadarConfig rc;
    rc.boresight_yaw_deg = 0.0;
    rc.mount_y_m = 0.0;
    sensor = SensorGeometry::FromConfig(rc, pulse);
  }
  std::vector<float> Scan(const OccupancyGrid& grid, std::vector<int>* lit = nullptr) const {
    const SimEnvironment env(grid, radar, 1);
    RadarSimulator sim(env, pulse, sensor, radar);
    std::vector<float> scan = sim.Simulate({0.0, 0.0, 0.0}, nullptr);
    if (lit) *lit = sim.lit_cells();
    return scan;
  }
  double Bin() const { return RangeBinSizeM(pulse); }
};

/// Index and value of the largest |sample| in [from, to).
std::pair<int, double> Peak(const std::vector<float>& s, int from = 0, int to = -1) {
  if (to < 0) to = static_cast<int>(s.size());
  int best = from;
  for (int k = from; k < to; ++k) {
    if (std::abs(s[k]) > std::abs(s[best])) best = k;
  }
  return {best, std::abs(s[best])};
}

/// Matched-filter fit of one echo near `around`: the delay (samples) maximising the
/// correlation with the pulse model, and the least-squares amplitude there (signed).
struct EchoFit {
  double delay_samples = 0.0;
  double amplitude = 0.0;
};
EchoFit FitEcho(const std::vector<float>& s, const PulseConfig& pulse, int around) {
  const GaussianPulse model(pulse);
  const double fs = pulse.sampling_frequency_hz;
  EchoFit best;
  double best_score = -1.0;
  for (double tau = around - 5.0; tau <= around + 5.0; tau += 0.01) {
    double sp = 0.0, pp = 0.0;
    for (int k = std::max(0, around - 40); k < std::min(static_cast<int>(s.size()), around + 40);
         ++k) {
      const double p = model((k - tau) / fs);
      sp += s[k] * p;
      pp += p * p;
    }
    if (sp * sp / pp > best_score) {
      best_score = sp * sp / pp;
      best = {tau, sp / pp};
    }
  }
  return best;
}

double Energy(const std::vector<float>& s, int from, int to) {
  double e = 0.0;
  for (int k = from; k < to; ++k) e += double(s[k]) * s[k];
  return e;
}

const OccupancyGrid kEmpty = FreeGrid(100, 100, 0.05, -2.5, -2.5);

TEST(RadarSimulatorTest, PointTargetEchoSitsAtTwoROverC) {
  Rig rig;
  rig.radar.point_targets = {{1.5, 0.0, 1.0}};
  const std::vector<float> scan = rig.Scan(kEmpty);
  const EchoFit fit = FitEcho(scan, rig.pulse, Peak(scan).first);
  EXPECT_NEAR(fit.delay_samples * rig.Bin(), 1.5, 0.002);  // 2R/c * fs samples
  // On boresight: |amplitude| = sqrt(RCS) / R^2 (times the pulse's own amplitude).
  EXPECT_NEAR(std::abs(fit.amplitude), 1.0 / (1.5 * 1.5), 0.01);
}

TEST(RadarSimulatorTest, RangeOffsetShiftsTheEcho) {
  Rig rig;
  rig.radar.point_targets = {{1.5, 0.0, 1.0}};
  rig.sensor.range_offset_m = 0.3;
  const std::vector<float> scan = rig.Scan(kEmpty);
  const EchoFit fit = FitEcho(scan, rig.pulse, Peak(scan).first);
  EXPECT_NEAR(0.3 + fit.delay_samples * rig.Bin(), 1.5, 0.002);
}

TEST(RadarSimulatorTest, AmplitudeFallsAsOneOverRSquared) {
  Rig rig;
  auto amplitude = [&](double range) {
    rig.radar.point_targets = {{range, 0.0, 1.0}};
    const std::vector<float> scan = rig.Scan(kEmpty);
    return std::abs(FitEcho(scan, rig.pulse, Peak(scan).first).amplitude);
  };
  EXPECT_NEAR(amplitude(1.0) / amplitude(2.0), 4.0, 0.04);
  EXPECT_NEAR(amplitude(0.5) / amplitude(1.0), 4.0, 0.04);
}

TEST(RadarSimulatorTest, BeamPatternIsMinus3dBAt30Degrees) {
  Rig rig;
  const double r = 1.5, a = 30.0 * M_PI / 180.0;
  auto amplitude = [&](double x, double y) {
    rig.radar.point_targets = {{x, y, 1.0}};
    const std::vector<float> scan = rig.Scan(kEmpty);
    return std::abs(FitEcho(scan, rig.pulse, Peak(scan).first).amplitude);
  };
  const double centre = amplitude(r, 0.0);
  EXPECT_NEAR(20.0 * std::log10(amplitude(r * std::cos(a), r * std::sin(a)) / centre), -3.0, 0.1);
  EXPECT_NEAR(20.0 * std::log10(amplitude(r * std::cos(a), -r * std::sin(a)) / centre), -3.0, 0.1);
  rig.radar.point_targets = {{-r, 0.0, 1.0}};  // behind the antenna: unseen
  EXPECT_EQ(Peak(rig.Scan(kEmpty)).second, 0.0);
}

TEST(RadarSimulatorTest, WallEchoAppearsAtItsRangeAndHidesWhatIsBehind) {
  Rig rig;
  OccupancyGrid grid = kEmpty;
  // A wall across the beam at x = 1.2 m (cells spanning 1.20 .. 1.25).
  for (double y = -1.0; y <= 1.0; y += 0.025) testing::Occupy(&grid, {1.22, y});
  rig.radar.point_targets = {{2.0, 0.0, 1.0}};  // behind the wall
  std::vector<int> lit;
  const std::vector<float> scan = rig.Scan(grid, &lit);
  EXPECT_FALSE(lit.empty());
  const int wall_bin = static_cast<int>(1.2 / rig.Bin());
  const int target_bin = static_cast<int>(2.0 / rig.Bin());
  // Nothing before the wall's face (1.2 m on boresight, less half a pulse); the strongest
  // echo comes from its nearest part.
  const int pulse_half = 24;
  EXPECT_EQ(Energy(scan, 0, wall_bin - pulse_half), 0.0);
  EXPECT_GT(Energy(scan, wall_bin - pulse_half, wall_bin + pulse_half), 0.0);
  const int k = Peak(scan).first;
  EXPECT_GE(k, wall_bin - 5);
  EXPECT_LE(k, static_cast<int>(1.45 / rig.Bin()));
  EXPECT_LT(Energy(scan, target_bin - 20, target_bin + 20), 1e-3 * Energy(scan, 0, 1000));
  // Without the wall the target shows.
  rig.radar.point_targets = {{2.0, 0.0, 1.0}};
  EXPECT_NEAR(Peak(rig.Scan(kEmpty)).first, target_bin, 3);
}

TEST(RadarSimulatorTest, CouplingPulseSitsAtRangeZero) {
  Rig rig;
  rig.radar.coupling_amplitude = 0.5;
  const std::vector<float> scan = rig.Scan(kEmpty);
  EXPECT_NEAR(scan[0], 0.5 * rig.pulse.amplitude_v, 1e-3);
  EXPECT_EQ(Energy(scan, 100, 1000), 0.0);
}

TEST(RadarSimulatorTest, ThermalNoiseHasTheConfiguredSpread) {
  Rig rig;
  rig.radar.noise_std = 0.01;
  const SimEnvironment env(kEmpty, rig.radar, 1);
  RadarSimulator sim(env, rig.pulse, rig.sensor, rig.radar);
  std::mt19937_64 rng(5);
  const std::vector<float> scan = sim.Simulate({0, 0, 0}, &rng);
  const double rms = std::sqrt(Energy(scan, 0, 1000) / 1000);
  EXPECT_NEAR(rms, 0.01, 0.001);
  EXPECT_EQ(Energy(sim.Simulate({0, 0, 0}, nullptr), 0, 1000), 0.0);
}

TEST(RadarSimulatorTest, SensorPoseMovesTheEcho) {
  // The same wall seen from 0.5 m closer starts 0.5 m earlier in the scan.
  Rig rig;
  OccupancyGrid grid = kEmpty;
  WallAlongX(&grid, 1.52, -2.0, 2.0);
  rig.sensor.T_robot_sensor = {0, 0, M_PI / 2};
  const SimEnvironment env(grid, rig.radar, 1);
  RadarSimulator sim(env, rig.pulse, rig.sensor, rig.radar);
  // Leading edge: the first sample above 5 % of the scan's peak.
  auto leading_edge = [&](const std::vector<float>& s) {
    const double peak = Peak(s).second;
    int k = 0;
    while (std::abs(s[k]) < 0.05 * peak) ++k;
    return k * rig.Bin();
  };
  const double far = leading_edge(sim.Simulate({0.0, 0.0, M_PI / 2}, nullptr));
  const double near = leading_edge(sim.Simulate({0.0, 0.5, M_PI / 2}, nullptr));
  EXPECT_NEAR(far - near, 0.5, 0.05);
}

}  // namespace
}  // namespace uwbsar::sim
