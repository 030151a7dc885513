// The contracts of imaging/factorized_back_projection.h that do not need a whole run: the result
// does not depend on the threads, scans whose sectors do not fit one polar grid are imaged
// directly, paper profiles without their quadrature and bad imaging.ffbp settings are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/config_io.h"
#include "drivers/sim/echo_simulator.h"
#include "imaging/factorized_back_projection.h"
#include "imaging/range_profile.h"
#include "slam/app_config.h"

namespace uwbsar {
namespace {

struct Scans {
  SensorGeometry geometry;
  std::vector<std::shared_ptr<const RangeProfile>> profiles;
  std::vector<Pose2> T_grid_sensor;
};

/// `n` scans of the left radar of the default configuration echoing two point targets, the
/// antenna at `pose(i)`; paper-mode profiles with their quadrature.
template <class PoseOf>
Scans Simulate(int n, PoseOf pose) {
  const Config config;
  Scans s;
  s.geometry = SensorGeometry::FromConfig(config.radars[0], config.pulse);
  RangeCompressor compressor(config.pulse, s.geometry, /*coherent=*/false, 1, /*quadrature=*/true);
  EchoSimulator sim(config.pulse, s.geometry, EchoModel{});
  const std::vector<Scatterer> scene = {{{0.3, 1.2}, 1.0}, {{-0.2, 2.0}, 1.0}};
  std::mt19937_64 rng(5);
  for (int i = 0; i < n; ++i) {
    s.T_grid_sensor.push_back(pose(i));
    s.profiles.push_back(compressor.Compress(sim.Simulate(s.T_grid_sensor.back(), scene, &rng)));
  }
  return s;
}

cv::Mat Image(const Scans& s, const ImageGrid& grid, int threads) {
  const Config config;
  cv::Mat image = MakeSarImage(grid, false);
  FactorizedBackProjector ffbp(config.imaging.ffbp,
                               PolarSamplingFor(config.imaging.ffbp, config.pulse, false), threads);
  for (std::size_t i = 0; i < s.profiles.size(); ++i) {
    ffbp.Add(s.profiles[i], s.T_grid_sensor[i], s.geometry, grid, &image);
  }
  ffbp.Flush(grid, &image);
  EXPECT_EQ(ffbp.pending_scans(), 0);
  return image;
}

TEST(FactorizedBackProjectorTest, TheImageDoesNotDependOnTheThreads) {
  // 100 scans 4 mm apart along x, looking left (+y): a top sub-aperture and a flushed rest.
  const Scans s = Simulate(100, [](int i) { return Pose2{-0.2 + 0.004 * i, 0.0, M_PI / 2}; });
  const ImageGrid grid = ImageGrid::Covering(-2.0, 2.0, 0.0, 3.2, 0.005);
  const cv::Mat one = Image(s, grid, 1), two = Image(s, grid, 2);
  EXPECT_EQ(cv::norm(one, two, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(one, cv::NORM_INF), 0.0);
}

TEST(FactorizedBackProjectorTest, ScansTurningOnTheSpotAreImagedDirectly) {
  // One antenna turning through 270 deg on the spot: no polar grid about it holds every
  // sector, so each scan is back-projected directly and the image equals direct's exactly.
  const Scans s = Simulate(16, [](int i) { return Pose2{0.0, 0.0, 0.3 * i}; });
  const ImageGrid grid = ImageGrid::Covering(-3.2, 3.2, -3.2, 3.2, 0.01);
  cv::Mat direct = MakeSarImage(grid, false);
  BackProjector projector(1);
  for (std::size_t i = 0; i < s.profiles.size(); ++i) {
    projector.Accumulate(*s.profiles[i], s.T_grid_sensor[i], s.geometry, grid, &direct);
  }
  EXPECT_GT(cv::norm(direct, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(Image(s, grid, 1), direct, cv::NORM_INF), 0.0);
}

TEST(FactorizedBackProjectorTest, PaperProfilesWithoutTheirQuadratureAreRefused) {
  const Config config;
  const SensorGeometry g = SensorGeometry::FromConfig(config.radars[0], config.pulse);
  RangeCompressor compressor(config.pulse, g, false, 1);  // no quadrature
  const auto profile = compressor.Compress(std::vector<float>(1000, 0.0f));
  const ImageGrid grid = ImageGrid::Covering(-1, 1, 0, 3, 0.01);
  cv::Mat image = MakeSarImage(grid, false);
  FactorizedBackProjector ffbp(config.imaging.ffbp,
                               PolarSamplingFor(config.imaging.ffbp, config.pulse, false), 1);
  EXPECT_THROW(ffbp.Add(profile, Pose2{0, 0, M_PI / 2}, g, grid, &image), std::invalid_argument);
}

TEST(FactorizedBackProjectorTest, SettingsOutOfRangeAreRefusedNamingTheKey) {
  ImagingConfig imaging;
  imaging.ffbp.merge_factor = 1;
  try {
    Validate(imaging, "robot.yaml");
    FAIL() << "merge_factor 1 accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("imaging.ffbp.merge_factor"), std::string::npos);
  }
  imaging = ImagingConfig();
  imaging.ffbp.base_scans = 64;
  imaging.ffbp.levels = 8;  // 64 * 2^8 scans per sub-aperture
  EXPECT_THROW(Validate(imaging, "robot.yaml"), ConfigError);
}

}  // namespace
}  // namespace uwbsar
