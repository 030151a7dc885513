// The frontend's contract on bad input, gating and tiles.
#include "frontend/imaging_frontend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "drivers/sim/synthetic_run.h"
#include "slam/app_config.h"

namespace uwbsar {
namespace {

// A short run over one point target, with scans of a smaller pixel budget.
struct Fixture {
  Config config;
  SyntheticRun run;
  Fixture(double length_m = 1.0) {
    config.imaging.pixel_size_m = 0.02;
    SyntheticPath path;
    path.length_m = length_m;
    path.speed_mps = 0.5;
    path.radar_rate_hz = 50;
    run = SimulateRun(config, path, {{{0.5, 1.2}, 1.0}}, EchoModel{}, 1);
  }
};

void Feed(ImagingFrontend* f, const SyntheticRun& run) {
  std::size_t i = 0, j = 0;
  while (i < run.odometry.size() || j < run.scans.size()) {
    if (j >= run.scans.size() ||
        (i < run.odometry.size() && run.odometry[i].stamp_ns <= run.scans[j].stamp_ns)) {
      f->AddOdometry(run.odometry[i++]);
    } else {
      f->AddScan(run.scans[j++]);
    }
  }
  f->Finish();
}

double ImageSum(const std::vector<Keyframe>& kfs) {
  double s = 0;
  for (const Keyframe& k : kfs) s += cv::sum(cv::abs(k.image))[0];
  return s;
}

TEST(ImagingFrontendTest, CleanRunImagesEveryMovingScan) {
  Fixture fx;
  ImagingFrontend f(fx.config);
  Feed(&f, fx.run);
  const FrontendStats& s = f.stats();
  EXPECT_EQ(s.scans_received, static_cast<long long>(fx.run.scans.size()));
  EXPECT_EQ(s.scans_rejected(), 0);
  // 0.5 m/s at 50 Hz = 10 mm per scan: every scan passes the 3 mm gate.
  EXPECT_EQ(s.scans_imaged, s.scans_received);
  EXPECT_GT(s.pixel_updates, 0);
}

TEST(ImagingFrontendTest, StationaryRobotScansAreGated) {
  Fixture fx;
  for (auto& o : fx.run.odometry) o.T_world_robot = Pose2{};  // robot never moves
  ImagingFrontend f(fx.config);
  Feed(&f, fx.run);
  EXPECT_EQ(f.stats().scans_imaged, 2);  // the first scan of each radar only
  EXPECT_EQ(f.stats().scans_gated, f.stats().scans_received - 2);
}

TEST(ImagingFrontendTest, BadScansAreCountedAndNeverReachTiles) {
  Fixture fx;
  ImagingFrontend clean(fx.config);
  Feed(&clean, fx.run);
  const double clean_sum = ImageSum(clean.TakeKeyframes());

  SyntheticRun bad = fx.run;
  RadarScan nan_scan = bad.scans[10];
  nan_scan.samples[500] = std::numeric_limits<float>::quiet_NaN();
  RadarScan inf_scan = bad.scans[12];
  inf_scan.samples[3] = std::numeric_limits<float>::infinity();
  RadarScan empty = bad.scans[14];
  empty.samples.clear();
  RadarScan short_scan = bad.scans[16];
  short_scan.samples.resize(700);
  RadarScan long_scan = bad.scans[18];
  long_scan.samples.resize(1500, 1.0f);
  RadarScan unknown = bad.scans[20];
  unknown.sensor_id = 7;
  for (const RadarScan& s : {nan_scan, inf_scan, empty, short_scan, long_scan, unknown}) {
    bad.scans.push_back(s);
  }
  std::stable_sort(bad.scans.begin(), bad.scans.end(),
                   [](const RadarScan& a, const RadarScan& b) { return a.stamp_ns < b.stamp_ns; });
  ImagingFrontend f(fx.config);
  Feed(&f, bad);
  const FrontendStats& s = f.stats();
  EXPECT_EQ(s.scans_rejected_nonfinite, 2);
  EXPECT_EQ(s.scans_rejected_empty, 1);
  EXPECT_EQ(s.scans_rejected_length, 2);
  EXPECT_EQ(s.scans_rejected_unknown_sensor, 1);
  // The tiles equal the clean run's: nothing of the bad scans was imaged.
  EXPECT_NEAR(ImageSum(f.TakeKeyframes()), clean_sum, 1e-6 * clean_sum);
}

TEST(ImagingFrontendTest, OdometryJumpIsCorrectedNotImagedAsTeleport) {
  Fixture fx(2.0);
  SyntheticRun jumped = fx.run;
  // From the middle on, the odometry reports the robot 5 m away (driver reset).
  for (std::size_t i = jumped.odometry.size() / 2; i < jumped.odometry.size(); ++i) {
    jumped.odometry[i].T_world_robot = Pose2{5.0, -3.0, 0.0} * jumped.odometry[i].T_world_robot;
  }
  ImagingFrontend f(fx.config);
  Feed(&f, jumped);
  EXPECT_EQ(f.stats().odometry_jumps_corrected, 1);
  // Faster than any robot, but the next samples agree with it: a reset, not an outlier.
  EXPECT_EQ(f.stats().odometry_rejected_implausible, 0);
  // The corrected path stays continuous: travelled distance ~ 2 m, not 7+ m.
  const auto kfs = f.TakeKeyframes();
  ASSERT_FALSE(kfs.empty());
  const double path_end = kfs.back().path_end_m;
  EXPECT_LT(path_end, 2.1);
  EXPECT_GT(path_end, 1.8);
}

// One odometry sample at an impossible speed, turn rate or coordinate (x = 1e20
// used to abort in an OpenCV allocation of 9 TB; 1e300 gave a garbage trajectory) is
// dropped and counted; what is imaged equals the clean run.
TEST(ImagingFrontendTest, OdometryOutlierAtImpossibleSpeedIsDroppedNotImaged) {
  Fixture fx(2.0);
  ImagingFrontend clean(fx.config);
  Feed(&clean, fx.run);
  const auto clean_kfs = clean.TakeKeyframes();
  ASSERT_FALSE(clean_kfs.empty());
  const double clean_sum = ImageSum(clean_kfs);
  struct Outlier {
    const char* what;
    Pose2 pose;
    bool implausible;  ///< counted as implausible (else as non-finite / absurd coordinate)
  };
  const std::size_t mid = fx.run.odometry.size() / 2;
  const Pose2 p = fx.run.odometry[mid].T_world_robot;
  const Outlier outliers[] = {
      {"x + 100 km", {p.x_m + 1e5, p.y_m, p.yaw_rad}, true},
      {"y - 1 m", {p.x_m, p.y_m - 1.0, p.yaw_rad}, true},
      {"yaw + 3 rad", {p.x_m, p.y_m, NormalizeAngle(p.yaw_rad + 3.0)}, true},
      {"x = 1e20", {1e20, p.y_m, p.yaw_rad}, false},
      {"x = 1e300", {1e300, p.y_m, p.yaw_rad}, false},
  };
  for (const Outlier& o : outliers) {
    for (const std::size_t at : {mid, fx.run.odometry.size() - 1}) {  // middle, and last
      SyntheticRun bad = fx.run;
      bad.odometry[at].T_world_robot = o.pose;
      ImagingFrontend f(fx.config);
      Feed(&f, bad);
      const FrontendStats& s = f.stats();
      EXPECT_EQ(s.odometry_rejected_implausible, o.implausible ? 1 : 0) << o.what << " at " << at;
      EXPECT_EQ(s.odometry_rejected_nonfinite, o.implausible ? 0 : 1) << o.what << " at " << at;
      EXPECT_EQ(s.odometry_jumps_corrected, 0) << o.what;
      const auto kfs = f.TakeKeyframes();
      ASSERT_EQ(kfs.size(), clean_kfs.size()) << o.what;
      // The dropped sample lies on a straight constant-speed path: interpolating across
      // it gives the same poses, so the tiles are the clean ones (without the last sample,
      // the scans after the one before it have no odometry: at most a scan less).
      const double tolerance = at == mid ? 1e-4 : 2e-2;
      EXPECT_NEAR(ImageSum(kfs), clean_sum, tolerance * clean_sum) << o.what << " at " << at;
      EXPECT_NEAR(kfs.back().path_end_m, clean_kfs.back().path_end_m, 0.02) << o.what;
    }
  }
}

TEST(ImagingFrontendTest, OutOfOrderAndNonFiniteOdometryAreRejected) {
  Fixture fx;
  ImagingFrontend f(fx.config);
  f.AddOdometry(fx.run.odometry[5]);
  f.AddOdometry(fx.run.odometry[3]);  // older than the last
  OdometrySample nan = fx.run.odometry[6];
  nan.T_world_robot.yaw_rad = std::nan("");
  f.AddOdometry(nan);
  EXPECT_EQ(f.stats().odometry_rejected_out_of_order, 1);
  EXPECT_EQ(f.stats().odometry_rejected_nonfinite, 1);
}

TEST(ImagingFrontendTest, ScansWithoutOdometryAreDroppedNotImaged) {
  Fixture fx;
  ImagingFrontend f(fx.config);
  for (const RadarScan& s : fx.run.scans) f.AddScan(s);  // odometry never arrives
  f.Finish();
  EXPECT_EQ(f.stats().scans_imaged, 0);
  EXPECT_EQ(f.stats().scans_rejected_stale + f.stats().scans_rejected_no_odometry,
            f.stats().scans_received);
}

// Live over DDS the first odometry sample can come after scans stamped later than it:
// they wait for it (as for any later odometry) and are imaged as in stamp order.
TEST(ImagingFrontendTest, ScansThatArriveBeforeTheFirstOdometryWaitForIt) {
  Fixture fx;
  ImagingFrontend in_order(fx.config);
  Feed(&in_order, fx.run);
  ImagingFrontend late_odometry(fx.config);
  std::size_t j = 0;  // the scans of the first 0.2 s before any odometry
  const TimestampNs t0 = fx.run.odometry.front().stamp_ns;
  for (; j < fx.run.scans.size() && fx.run.scans[j].stamp_ns < t0 + 200000000; ++j) {
    late_odometry.AddScan(fx.run.scans[j]);
  }
  EXPECT_EQ(late_odometry.stats().scans_rejected(), 0);
  std::size_t i = 0;
  while (i < fx.run.odometry.size() || j < fx.run.scans.size()) {
    if (j >= fx.run.scans.size() ||
        (i < fx.run.odometry.size() && fx.run.odometry[i].stamp_ns <= fx.run.scans[j].stamp_ns)) {
      late_odometry.AddOdometry(fx.run.odometry[i++]);
    } else {
      late_odometry.AddScan(fx.run.scans[j++]);
    }
  }
  late_odometry.Finish();
  EXPECT_EQ(late_odometry.stats().scans_imaged, in_order.stats().scans_imaged);
  EXPECT_EQ(late_odometry.stats().scans_rejected(), in_order.stats().scans_rejected());
}

TEST(ImagingFrontendTest, TilesOverlapByHalfAndHoldTheirScanPoses) {
  Fixture fx(4.5);
  ImagingFrontend f(fx.config);
  Feed(&f, fx.run);
  const auto kfs = f.TakeKeyframes();
  // Tiles start every 1 m over 4.5 m of path: 0, 1, 2 complete, 3 cut short (a
  // tile starting at 4 m would hold only scans that tile 3 holds).
  ASSERT_EQ(kfs.size(), 4u);
  for (std::size_t i = 0; i < kfs.size(); ++i) {
    EXPECT_NEAR(kfs[i].path_begin_m, static_cast<double>(i), 0.02);
    EXPECT_EQ(kfs[i].complete, i < 3);
    ASSERT_FALSE(kfs[i].scans.empty());
    // Anchored at the middle of the tile's path.
    const double mid = 0.5 * (kfs[i].path_begin_m + kfs[i].path_end_m);
    EXPECT_NEAR(kfs[i].T_world_robot.x_m, mid, 0.011);
    // The anchor is the lattice point next to the robot, with world orientation.
    const double half_pixel = 0.5 * fx.config.imaging.pixel_size_m + 1e-9;
    EXPECT_NEAR(kfs[i].T_world_anchor.x_m, kfs[i].T_world_robot.x_m, half_pixel);
    EXPECT_NEAR(kfs[i].T_world_anchor.y_m, kfs[i].T_world_robot.y_m, half_pixel);
    EXPECT_EQ(kfs[i].T_world_anchor.yaw_rad, 0.0);
  }
  // Consecutive tiles share the scans of their overlapping metre.
  for (std::size_t i = 0; i + 1 < kfs.size(); ++i) {
    const auto& next = kfs[i + 1].scans;
    const TimestampNs last = kfs[i].scans.back().stamp_ns;
    EXPECT_TRUE(std::any_of(next.begin(), next.end(),
                            [&](const ImagedScan& s) { return s.stamp_ns == last; }));
    EXPECT_GT(kfs[i].scans.back().stamp_ns, next.front().stamp_ns);
  }
}

TEST(ImagingFrontendTest, TilePixelsMapToTheWorldThroughTheAnchor) {
  // The point target must appear in a tile at T_anchor^-1 * p_world.
  Fixture fx(2.0);
  fx.config.imaging.pixel_size_m = 0.005;
  fx.config.imaging.mode = ImagingMode::kCoherent;
  ImagingFrontend f(fx.config);
  Feed(&f, fx.run);
  const auto kfs = f.TakeKeyframes();
  ASSERT_FALSE(kfs.empty());
  const Keyframe& k = kfs.front();
  std::vector<cv::Mat> parts;
  cv::split(k.image, parts);
  cv::Mat mag;
  cv::magnitude(parts[0], parts[1], mag);
  cv::Point peak;
  cv::minMaxLoc(mag, nullptr, nullptr, nullptr, &peak);
  const Point2 in_tile = k.grid.PixelToMetric(peak.x, peak.y);
  const Point2 world = k.T_world_anchor * in_tile;
  EXPECT_NEAR(world.x_m, 0.5, 0.01);
  EXPECT_NEAR(world.y_m, 1.2, 0.01);
}

TEST(ImagingFrontendTest, SameInputGivesBitIdenticalTiles) {
  Fixture fx;
  ImagingFrontend a(fx.config), b(fx.config);
  Feed(&a, fx.run);
  Feed(&b, fx.run);
  const auto ka = a.TakeKeyframes(), kb = b.TakeKeyframes();
  ASSERT_EQ(ka.size(), kb.size());
  for (std::size_t i = 0; i < ka.size(); ++i) {
    EXPECT_EQ(cv::norm(ka[i].image, kb[i].image, cv::NORM_INF), 0.0);
  }
}

}  // namespace
}  // namespace uwbsar
