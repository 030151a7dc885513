// Imaging acceptance: point targets and a wall,
// simulated with the pulse at delay 2R/c, imaged by the frontend in both modes.
#include "imaging/back_projection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "slam/app_config.h"
#include "test/frontend/imaging_scenario.h"

namespace uwbsar {
namespace {

using testing::ConfigForMode;
using testing::PaperDetection;

// Targets well inside the aperture of a 3 m straight pass (full +-30 deg view),
// separated so that no target lies on another's range or cross-range cut.
const std::vector<Point2> kTargets = {{1.2, 1.0}, {1.8, 2.0}, {1.5, -1.4}};

// lambda / (4 sin 30 deg) with lambda = c / fc.
constexpr double kTheoreticalCrossRangeM = 299792458.0 / 7.29e9 / (4 * 0.5);

struct ModeResult {
  std::vector<PsfMetrics> psf;        ///< the paper's detection of the real image
  std::vector<PsfMetrics> magnitude;  ///< |image| (the coherent mode's own detection)
};

ModeResult ImagePointTargets(const char* mode, const SyntheticPath& path) {
  const Config config = ConfigForMode(mode);
  std::vector<Scatterer> scene;
  for (const Point2& t : kTargets) scene.push_back({t, 1.0});
  const SyntheticRun run = SimulateRun(config, path, scene, EchoModel{}, 7);
  const slam::StripResult result = slam::ImageRun(config, run.odometry, run.scans);
  const cv::Mat detected = PaperDetection(config, result.strip.image);
  const cv::Mat magnitude = MagnitudeImage(result.strip.image);
  ModeResult out;
  for (const Point2& t : kTargets) {
    // Range direction: from the closest point of the path to the target.
    double best = 1e9;
    Point2 closest;
    for (double s = 0; s <= path.length_m; s += 0.01) {
      const Pose2 p = PathPose(path, s);
      const double d = std::hypot(t.x_m - p.x_m, t.y_m - p.y_m);
      if (d < best) best = d, closest = {p.x_m, p.y_m};
    }
    const Point2 range_dir{t.x_m - closest.x_m, t.y_m - closest.y_m};
    out.psf.push_back(MeasurePsf(detected, result.strip.grid, t, range_dir));
    out.magnitude.push_back(MeasurePsf(magnitude, result.strip.grid, t, range_dir));
  }
  return out;
}

void Print(const char* mode, const std::vector<PsfMetrics>& psf) {
  for (std::size_t i = 0; i < psf.size(); ++i) {
    const PsfMetrics& m = psf[i];
    std::printf(
        "%-12s target (%.1f, %.1f): error %.2f mm, -3 dB range %.1f mm, cross-range "
        "%.1f mm, PSLR %.1f dB, peak %.1f\n",
        mode, kTargets[i].x_m, kTargets[i].y_m, m.position_error_m * 1e3, m.range_width_m * 1e3,
        m.cross_range_width_m * 1e3, m.pslr_db, m.peak_value);
  }
}

TEST(BackProjectionTest, PointTargetsFocusAtTruePositionInBothModes) {
  const SyntheticPath straight;  // 3 m along +x
  const ModeResult paper = ImagePointTargets("paper", straight);
  const ModeResult coherent = ImagePointTargets("coherent", straight);
  Print("paper", paper.psf);
  Print("coherent", coherent.psf);
  Print("coherent |I|", coherent.magnitude);
  for (std::size_t i = 0; i < kTargets.size(); ++i) {
    for (const ModeResult* r : {&paper, &coherent}) {
      ASSERT_TRUE(r->psf[i].found);
      EXPECT_LT(r->psf[i].position_error_m, 0.01) << "target " << i;
    }
    EXPECT_LT(coherent.magnitude[i].position_error_m, 0.01) << i;
    EXPECT_LT(coherent.magnitude[i].cross_range_width_m, 1.5 * kTheoreticalCrossRangeM) << i;
    EXPECT_LT(coherent.psf[i].cross_range_width_m, 1.5 * kTheoreticalCrossRangeM) << i;
    // Coherent must be at least as good as paper on every figure (widths within
    // 1 %, a twentieth of a pixel: both are set by the geometry, not interpolation).
    EXPECT_LE(coherent.psf[i].cross_range_width_m, 1.01 * paper.psf[i].cross_range_width_m) << i;
    EXPECT_LE(coherent.psf[i].range_width_m, 1.01 * paper.psf[i].range_width_m) << i;
    EXPECT_LE(coherent.psf[i].pslr_db, paper.psf[i].pslr_db) << i;
    // Exact interpolation keeps the coherent gain that linear interpolation of
    // the raw carrier loses (up to 5 dB).
    EXPECT_GT(coherent.psf[i].peak_value, paper.psf[i].peak_value) << i;
    EXPECT_LE(coherent.psf[i].position_error_m, paper.psf[i].position_error_m + 0.002) << i;
  }
}

}  // namespace
}  // namespace uwbsar

namespace uwbsar {
namespace {

TEST(BackProjectionTest, FlatWallIsStraightRidgeAtItsDistance) {
  constexpr double kWallY = 1.5;
  for (const char* mode : {"paper", "coherent"}) {
    const Config config = ConfigForMode(mode);
    const SyntheticPath path;  // 3 m along +x at y = 0
    const auto wall = WallScatterers({-0.5, kWallY}, {3.5, kWallY}, 0.004, 0.05);
    const SyntheticRun run = SimulateRun(config, path, wall, EchoModel{}, 3);
    const slam::StripResult result = slam::ImageRun(config, run.odometry, run.scans);
    const cv::Mat detected = config.imaging.coherent() ? MagnitudeImage(result.strip.image)
                                                       : PaperDetection(config, result.strip.image);
    const ImageGrid& g = result.strip.grid;
    double worst = 0.0;
    int columns = 0;
    for (double x = 0.0; x <= path.length_m; x += 0.05) {
      const int col = static_cast<int>(std::lround(g.XToCol(x)));
      const int r_lo = static_cast<int>(g.YToRow(kWallY + 0.4));
      const int r_hi = static_cast<int>(g.YToRow(kWallY - 0.4));
      int best_row = r_lo;
      for (int r = r_lo; r <= r_hi; ++r) {
        if (detected.at<float>(r, col) > detected.at<float>(best_row, col)) best_row = r;
      }
      const double a = detected.at<float>(best_row - 1, col), b = detected.at<float>(best_row, col),
                   c = detected.at<float>(best_row + 1, col);
      const double offset = 0.5 * (a - c) / (a - 2 * b + c);
      worst = std::max(worst, std::abs(g.RowToY(best_row + offset) - kWallY));
      ++columns;
    }
    std::printf("%-8s wall ridge: worst offset from 1.5 m over %d columns along 3 m: %.2f mm\n",
                mode, columns, worst * 1e3);
    EXPECT_LT(worst, 0.01) << mode;
  }
}

TEST(BackProjectionTest, CurvedPathStillFocusesPointTargets) {
  SyntheticPath arc;
  arc.turn_radius_m = 4.0;  // constant left turn, 3 m of arc (43 deg)
  arc.length_m = 3.0;
  // Targets beside the middle of the arc, inside and outside the turn.
  const Pose2 mid = PathPose(arc, 1.5);
  const std::vector<Point2> targets = {mid * Point2{0.0, 1.3}, mid * Point2{0.3, -1.6}};
  std::vector<Scatterer> scene;
  for (const Point2& t : targets) scene.push_back({t, 1.0});
  for (const char* mode : {"paper", "coherent"}) {
    const Config config = ConfigForMode(mode);
    const SyntheticRun run = SimulateRun(config, arc, scene, EchoModel{}, 5);
    const slam::StripResult result = slam::ImageRun(config, run.odometry, run.scans);
    const cv::Mat detected = config.imaging.coherent() ? MagnitudeImage(result.strip.image)
                                                       : PaperDetection(config, result.strip.image);
    for (const Point2& t : targets) {
      const Point2 range_dir{t.x_m - mid.x_m, t.y_m - mid.y_m};
      const PsfMetrics m = MeasurePsf(detected, result.strip.grid, t, range_dir);
      std::printf("%-8s arc target (%.2f, %.2f): error %.2f mm, cross-range %.1f mm\n", mode, t.x_m,
                  t.y_m, m.position_error_m * 1e3, m.cross_range_width_m * 1e3);
      ASSERT_TRUE(m.found);
      EXPECT_LT(m.position_error_m, 0.01);
      EXPECT_LT(m.cross_range_width_m, 1.5 * 1.3 * kTheoreticalCrossRangeM);
    }
  }
}

TEST(BackProjectionTest, IgnoringTheTurnDefocuses) {
  // The same arc imaged as if the robot had driven straight: the focus is lost,
  // which shows the poses are used in full (the previous test is not trivial).
  SyntheticPath arc;
  arc.turn_radius_m = 4.0;
  const Pose2 mid = PathPose(arc, 1.5);
  const Point2 target = mid * Point2{0.0, 1.3};
  const Config config = ConfigForMode("coherent");
  SyntheticRun run = SimulateRun(config, arc, {{target, 1.0}}, EchoModel{}, 5);
  const slam::StripResult good = slam::ImageRun(config, run.odometry, run.scans);
  SyntheticPath straight;
  for (auto& o : run.odometry) {
    o.T_world_robot =
        PathPose(straight, std::min(3.0, NsToSeconds(o.stamp_ns - straight.start_stamp_ns) * 0.2));
  }
  const slam::StripResult bad = slam::ImageRun(config, run.odometry, run.scans);
  double good_peak = 0, bad_peak = 0;
  cv::minMaxLoc(MagnitudeImage(good.strip.image), nullptr, &good_peak);
  cv::minMaxLoc(MagnitudeImage(bad.strip.image), nullptr, &bad_peak);
  EXPECT_GT(good_peak, 1.5 * bad_peak);
}

}  // namespace
}  // namespace uwbsar
