// imaging.method ffbp against direct back-projection (the reference), through the frontend
// that forms keyframe tiles: the same scans, the same tile grids, compared tile by tile on the
// paper's detection (NCC) and on point targets (peak position, level, -3 dB widths). Both
// imaging modes, a straight pass and a turning one.
#include "imaging/factorized_back_projection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "drivers/logs/log_source.h"
#include "frontend/imaging_frontend.h"
#include "test/frontend/imaging_scenario.h"
#include "test/imaging/image_ncc.h"

namespace uwbsar {
namespace {

using testing::ConfigForMode;
using testing::PaperDetection;

std::vector<Keyframe> Tiles(const Config& config, const SyntheticRun& run) {
  ImagingFrontend frontend{ImagingFrontendConfig(config)};
  LogSource(run.odometry, run.scans).Run([&](const Message& m) {
    FeedScanOrOdometry(frontend, m);
  });
  frontend.Finish();
  return frontend.TakeKeyframes();
}

struct Comparison {
  double min_ncc = 1.0;
  std::vector<Keyframe> direct, ffbp;
};

Comparison CompareTiles(const char* mode, const SyntheticPath& path,
                        const std::vector<Scatterer>& scene) {
  Config config = ConfigForMode(mode);
  const SyntheticRun run = SimulateRun(config, path, scene, EchoModel{}, 11);
  Comparison c;
  config.imaging.method = ImagingMethod::kDirect;
  c.direct = Tiles(config, run);
  config.imaging.method = ImagingMethod::kFfbp;
  c.ffbp = Tiles(config, run);
  EXPECT_EQ(c.direct.size(), c.ffbp.size());
  for (std::size_t i = 0; i < std::min(c.direct.size(), c.ffbp.size()); ++i) {
    const Keyframe& d = c.direct[i];
    const Keyframe& f = c.ffbp[i];
    EXPECT_EQ(d.image.size(), f.image.size()) << "tile " << i;
    EXPECT_EQ(d.grid.x0_m, f.grid.x0_m) << "tile " << i;
    if (d.image.size() != f.image.size()) continue;
    // As features see them: the positive image (paper) or magnitude (coherent), blurred.
    const double ncc =
        ZeroMeanNcc(EnhancedFloat(d.image, config.enhance), EnhancedFloat(f.image, config.enhance));
    std::printf("%s tile %zu: NCC %.5f\n", mode, i, ncc);
    c.min_ncc = std::min(c.min_ncc, ncc);
  }
  return c;
}

/// A corridor like seed_lab's: two walls, a doorway's frame and a few poles and cabinets.
std::vector<Scatterer> Corridor() {
  std::vector<Scatterer> scene = WallScatterers({-0.5, 1.6}, {2.0, 1.6}, 0.01, 0.05);
  const std::vector<Scatterer> far = WallScatterers({2.8, 1.6}, {5.0, 1.6}, 0.01, 0.05);
  scene.insert(scene.end(), far.begin(), far.end());
  const std::vector<Scatterer> right = WallScatterers({-0.5, -1.8}, {5.0, -1.8}, 0.01, 0.05);
  scene.insert(scene.end(), right.begin(), right.end());
  const std::vector<Scatterer> jamb = WallScatterers({2.0, 1.6}, {2.0, 2.3}, 0.01, 0.05);
  scene.insert(scene.end(), jamb.begin(), jamb.end());
  for (int i = 0; i < 6; ++i) scene.push_back({{0.3 + 0.8 * i, i % 2 ? -1.2 : 1.1}, 0.5});
  return scene;
}

TEST(FfbpTest, CorridorTilesMatchDirectInBothModes) {
  SyntheticPath path;
  path.length_m = 4.0;
  for (const char* mode : {"paper", "coherent"}) {
    const Comparison c = CompareTiles(mode, path, Corridor());
    EXPECT_GE(c.min_ncc, 0.99) << mode;
  }
}

TEST(FfbpTest, TilesOfATurnMatchDirect) {
  SyntheticPath path;
  path.length_m = 4.0;
  path.turn_radius_m = 1.5;  // a quarter turn and more: sub-apertures on an arc
  const Comparison c = CompareTiles("paper", path, Corridor());
  EXPECT_GE(c.min_ncc, 0.99);
}

TEST(FfbpTest, PointTargetPeakLevelAndWidthMatchDirect) {
  SyntheticPath path;
  path.length_m = 3.0;
  const std::vector<Point2> targets = {{1.2, 1.0}, {1.8, 2.0}, {1.5, -1.4}};
  std::vector<Scatterer> scene;
  for (const Point2& t : targets) scene.push_back({t, 1.0});
  for (const char* mode : {"paper", "coherent"}) {
    Config config = ConfigForMode(mode);
    const SyntheticRun run = SimulateRun(config, path, scene, EchoModel{}, 7);
    std::vector<ImagedScan> scans;
    // The whole run on one world grid, scan by scan (direct) and by sub-apertures (ffbp), from
    // the same profiles (made for ffbp: with their quadrature, which direct ignores).
    config.imaging.method = ImagingMethod::kFfbp;
    ImagingFrontend frontend{ImagingFrontendConfig(config)};
    frontend.SetScanObserver([&](const ImagedScan& s) { scans.push_back(s); });
    LogSource(run.odometry, run.scans).Run([&](const Message& m) {
      FeedScanOrOdometry(frontend, m);
    });
    frontend.Finish();
    std::vector<Pose2> poses;
    for (const ImagedScan& s : scans) poses.push_back(s.T_world_robot);
    const ImageGrid grid = WorldGridCovering(poses, frontend.sensors(), 0.1, 0.005);
    cv::Mat direct = MakeSarImage(grid, config.imaging.coherent());
    cv::Mat ffbp = direct.clone();
    BackProjector projector(2);
    const PolarSampling sampling =
        PolarSamplingFor(config.imaging.ffbp, config.pulse, config.imaging.coherent());
    std::vector<FactorizedBackProjector> streams(
        frontend.sensors().size(), FactorizedBackProjector(config.imaging.ffbp, sampling, 2));
    for (const ImagedScan& s : scans) {
      const SensorGeometry& g = frontend.sensors()[static_cast<std::size_t>(s.sensor_id)];
      const Pose2 T = s.T_world_robot * g.T_robot_sensor;
      projector.Accumulate(*s.profile, T, g, grid, &direct);
      streams[static_cast<std::size_t>(s.sensor_id)].Add(s.profile, T, g, grid, &ffbp);
    }
    for (FactorizedBackProjector& f : streams) f.Flush(grid, &ffbp);
    const cv::Mat dd = PaperDetection(config, direct), fd = PaperDetection(config, ffbp);
    // Not asserted: isolated point targets are where direct's own interpolation artefacts
    // (which ffbp does not reproduce) weigh most; the tiles' NCC is asserted above.
    std::printf("%s: NCC of the point-target images %.4f\n", mode, ZeroMeanNcc(dd, fd));
    for (const Point2& t : targets) {
      const Point2 range_dir{0.0, t.y_m > 0 ? 1.0 : -1.0};
      const PsfMetrics a = MeasurePsf(dd, grid, t, range_dir);
      const PsfMetrics b = MeasurePsf(fd, grid, t, range_dir);
      ASSERT_TRUE(a.found && b.found) << mode;
      const double offset_m = std::hypot(a.peak.x_m - b.peak.x_m, a.peak.y_m - b.peak.y_m);
      const double level_db = 20.0 * std::log10(b.peak_value / a.peak_value);
      std::printf(
          "%-8s target (%.1f, %.1f): peak offset %.2f mm (from the truth %.2f / %.2f mm), level "
          "%+.3f dB, -3 dB range %.1f / %.1f mm, cross-range %.1f / %.1f mm (direct / ffbp)\n",
          mode, t.x_m, t.y_m, offset_m * 1e3, a.position_error_m * 1e3, b.position_error_m * 1e3,
          level_db, a.range_width_m * 1e3, b.range_width_m * 1e3, a.cross_range_width_m * 1e3,
          b.cross_range_width_m * 1e3);
      EXPECT_LE(offset_m, 0.001) << mode;
      EXPECT_LE(std::abs(level_db), 0.5) << mode;
      EXPECT_NEAR(b.range_width_m, a.range_width_m, 0.002) << mode;
      EXPECT_NEAR(b.cross_range_width_m, a.cross_range_width_m, 0.002) << mode;
    }
  }
}

}  // namespace
}  // namespace uwbsar
