// Ray casting, the scatterer environment and the fractional-delay pulse table.
#include "drivers/sim/sim_environment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "drivers/sim/grid_ray_caster.h"
#include "drivers/sim/pulse_table.h"
#include "imaging/pulse.h"
#include "test/drivers/sim_test_util.h"

namespace uwbsar::sim {
namespace {

using testing::FreeGrid;
using testing::Occupy;
using testing::WallAlongX;

bool Contains(const std::vector<int>& v, int x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

TEST(GridRayCasterTest, FirstHitIsTheWallAtItsDistance) {
  OccupancyGrid g = FreeGrid(60, 60, 0.05, -1.0, -1.0);
  WallAlongX(&g, 1.02, -1.0, 2.0);  // cells spanning y = 1.00 .. 1.05
  GridRayCaster caster(g);
  const RayHit hit = caster.FirstHit({0.01, 0.0}, M_PI / 2, 3.0);
  ASSERT_GE(hit.cell, 0);
  EXPECT_NEAR(hit.range_m, 1.0, 1e-9);
  // At 45 degrees the ray meets the wall after sqrt(2) m.
  EXPECT_NEAR(caster.FirstHit({0.01, 0.0}, M_PI / 4, 3.0).range_m, std::sqrt(2.0), 0.05);
  EXPECT_LT(caster.FirstHit({0.01, 0.0}, M_PI / 2, 0.9).cell, 0);   // out of range
  EXPECT_LT(caster.FirstHit({0.01, 0.0}, -M_PI / 2, 3.0).cell, 0);  // leaves the grid
}

TEST(GridRayCasterTest, RayFromOutsideTheGridEntersIt) {
  OccupancyGrid g = FreeGrid(20, 20, 0.05, 0.0, 0.0);
  const int cell = Occupy(&g, {0.52, 0.52});
  GridRayCaster caster(g);
  const RayHit hit = caster.FirstHit({-1.0, 0.52}, 0.0, 3.0);
  EXPECT_EQ(hit.cell, cell);
  EXPECT_NEAR(hit.range_m, 1.5, 1e-6);
}

TEST(GridRayCasterTest, LitCellsStopAtTheFirstSurfaceUnlessPenetrated) {
  OccupancyGrid g = FreeGrid(80, 80, 0.05, -2.0, -1.0);
  const std::vector<int> near = WallAlongX(&g, 1.02, -2.0, 2.0);
  const std::vector<int> far = WallAlongX(&g, 1.52, -2.0, 2.0);
  GridRayCaster caster(g);
  std::vector<int> lit;
  caster.LitCells({0.0, 0.0}, M_PI / 2, M_PI / 6, 3.0, 0.0, 0.005, &lit);
  // The near wall is lit across the +-30 deg sector (x within about +-0.58 m) ...
  int near_lit = 0;
  for (int c : near) near_lit += Contains(lit, c);
  EXPECT_GE(near_lit, 22);
  EXPECT_LE(near_lit, 26);
  // ... and hides the far one; each cell is listed once.
  for (int c : far) EXPECT_FALSE(Contains(lit, c));
  std::vector<int> sorted = lit;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::unique(sorted.begin(), sorted.end()), sorted.end());
  lit.clear();
  caster.LitCells({0.0, 0.0}, M_PI / 2, M_PI / 6, 3.0, 0.6, 0.005, &lit);
  int far_lit = 0;
  for (int c : far) far_lit += Contains(lit, c);
  EXPECT_GT(far_lit, 20);
}

TEST(GridRayCasterTest, TargetBehindAWallIsHidden) {
  OccupancyGrid g = FreeGrid(60, 60, 0.05, -1.0, -1.0);
  WallAlongX(&g, 1.02, -0.2, 0.2);
  GridRayCaster caster(g);
  EXPECT_FALSE(caster.Visible({0.0, 0.0}, {0.0, 1.6}, 0.075));
  EXPECT_TRUE(caster.Visible({0.0, 0.0}, {0.0, 0.8}, 0.075));
  EXPECT_TRUE(caster.Visible({0.0, 0.0}, {0.0, 1.03}, 0.075));  // standing on the wall
  EXPECT_TRUE(caster.Visible({0.0, 0.0}, {1.0, 1.6}, 0.075));   // beside the wall
}

TEST(SimEnvironmentTest, OccupiedCellsGetScatterersInsideThem) {
  OccupancyGrid g = FreeGrid(40, 40, 0.05, -1.0, -1.0);
  const std::vector<int> wall = WallAlongX(&g, 0.5, -0.5, 0.5);
  SimRadarConfig radar;
  radar.scatterers_per_cell = 3;
  const SimEnvironment env(g, radar, 7);
  EXPECT_EQ(env.num_occupied_cells(), static_cast<int>(wall.size()));
  EXPECT_EQ(env.scatterers().size(), 3 * wall.size());
  for (int cell : wall) {
    ASSERT_EQ(env.CellEnd(cell) - env.CellBegin(cell), 3);
    const Point2 centre = g.CellCenter(cell / g.cols, cell % g.cols);
    for (int i = env.CellBegin(cell); i < env.CellEnd(cell); ++i) {
      EXPECT_LE(std::abs(env.scatterers()[i].x_m - centre.x_m), 0.025 + 1e-12);
      EXPECT_LE(std::abs(env.scatterers()[i].y_m - centre.y_m), 0.025 + 1e-12);
    }
  }
  EXPECT_EQ(env.CellEnd(0) - env.CellBegin(0), 0);  // free cells have none
}

TEST(SimEnvironmentTest, CellRcsIsExponentialWithTheConfiguredMean) {
  OccupancyGrid g = FreeGrid(100, 100, 0.05, 0.0, 0.0);
  for (auto& v : g.cells) v = OccupancyGrid::kOccupied;
  SimRadarConfig radar;
  radar.cell_rcs_m2 = 0.02;
  const SimEnvironment env(g, radar, 3);
  double sum = 0.0, sum_sq = 0.0;
  for (int cell = 0; cell < 10000; ++cell) {
    double rcs = 0.0;
    for (int i = env.CellBegin(cell); i < env.CellEnd(cell); ++i) {
      const SimScatterer& s = env.scatterers()[i];
      rcs += double(s.in_phase) * s.in_phase + double(s.quadrature) * s.quadrature;
    }
    sum += rcs;
    sum_sq += rcs * rcs;
  }
  const double mean = sum / 10000, stddev = std::sqrt(sum_sq / 10000 - mean * mean);
  EXPECT_NEAR(mean, 0.02, 0.001);
  EXPECT_NEAR(stddev, 0.02, 0.002);  // exponential: std = mean (speckle)
}

TEST(SimEnvironmentTest, SameSeedSameWorldOtherSeedAnother) {
  OccupancyGrid g = FreeGrid(20, 20, 0.05, 0.0, 0.0);
  WallAlongX(&g, 0.5, 0.0, 1.0);
  const SimRadarConfig radar;
  const SimEnvironment a(g, radar, 11), b(g, radar, 11), c(g, radar, 12);
  ASSERT_EQ(a.scatterers().size(), c.scatterers().size());
  for (std::size_t i = 0; i < a.scatterers().size(); ++i) {
    EXPECT_EQ(a.scatterers()[i].x_m, b.scatterers()[i].x_m);
    EXPECT_EQ(a.scatterers()[i].in_phase, b.scatterers()[i].in_phase);
  }
  EXPECT_NE(a.scatterers()[0].x_m, c.scatterers()[0].x_m);
  EXPECT_NE(DeriveSeed(1, 2, 3), DeriveSeed(1, 2, 4));
  EXPECT_NE(DeriveSeed(1, 2, 3), DeriveSeed(2, 2, 3));
}

TEST(SimEnvironmentTest, PointTargetsReflectWithTheirRcs) {
  SimRadarConfig radar;
  radar.point_targets = {{1.0, 2.0, 0.25}};
  const SimEnvironment env(FreeGrid(4, 4, 0.05, 0, 0), radar, 1);
  ASSERT_EQ(env.point_targets().size(), 1u);
  EXPECT_DOUBLE_EQ(env.point_targets()[0].x_m, 1.0);
  EXPECT_FLOAT_EQ(std::abs(env.point_targets()[0].in_phase), 0.5f);
}

TEST(PulseTableTest, EchoMatchesThePulseModelAtFractionalDelays) {
  const PulseConfig pulse;
  const PulseTable table(pulse);
  const GaussianPulse model(pulse);
  const double fs = pulse.sampling_frequency_hz;
  for (double delay : {100.0, 100.37, 250.81}) {
    std::vector<float> scan(400, 0.0f), quad(400, 0.0f);
    table.AddEcho(delay, 1.0f, 0.0f, scan.data(), 400);
    table.AddEcho(delay, 0.0f, 1.0f, quad.data(), 400);
    double worst = 0.0, worst_q = 0.0;
    for (int k = 0; k < 400; ++k) {
      const double t = (k - delay) / fs;
      worst = std::max(worst, std::abs(scan[k] - model(t)));
      const double q = model.Envelope(t) * std::sin(2 * M_PI * pulse.center_frequency_hz * t);
      worst_q = std::max(worst_q, std::abs(quad[k] - q));
    }
    // 64 fractions per sample: delay error <= 1/128 sample, slope <= 2 pi fc / fs A per sample.
    EXPECT_LT(worst, 0.02 * pulse.amplitude_v) << delay;
    EXPECT_LT(worst_q, 0.02 * pulse.amplitude_v) << delay;
  }
}

TEST(PulseTableTest, EchoesAreClippedAtTheScanEdges) {
  const PulseTable table(PulseConfig{});
  std::vector<float> scan(100, 0.0f);
  table.AddEcho(-3.0, 1.0f, 0.0f, scan.data(), 100);
  table.AddEcho(98.5, 1.0f, 0.0f, scan.data(), 100);
  table.AddEcho(-500.0, 1.0f, 0.0f, scan.data(), 100);  // entirely outside
  table.AddEcho(900.0, 1.0f, 0.0f, scan.data(), 100);
  EXPECT_NE(scan[0], 0.0f);
  EXPECT_NE(scan[99], 0.0f);
  EXPECT_EQ(scan[50], 0.0f);
}

}  // namespace
}  // namespace uwbsar::sim
