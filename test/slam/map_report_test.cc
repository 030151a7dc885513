// slam/outputs/map_report.h: StageTimingTable (the stages' seconds, their sum and the wall time,
// the shares of the wall time, a note that the stages overlap on two threads) and the run's paths
// in drawing order, so that a straight run's ground truth and loops stay visible.
#include "slam/outputs/map_report.h"

#include <gtest/gtest.h>

namespace uwbsar::slam {
namespace {

TEST(MapReportTest, TimingTableSharesAreOfTheWallTimeAndSayTheStagesOverlap) {
  StageTimes t;
  t.imaging_s = 3.0;
  t.features_s = 2.0;
  t.matching_s = 1.0;
  t.optimization_s = 0.5;
  const ReportTable table = StageTimingTable(t, 4.0, true);
  ASSERT_EQ(table.rows.size(), 6u);
  EXPECT_EQ(table.rows[0], (std::vector<std::string>{"imaging", "feeding", "3.000", "75.0 %"}));
  EXPECT_EQ(table.rows[1][1], "keyframe");
  // The stages add up to more than the wall time: the table says both, and why.
  EXPECT_EQ(table.rows[4][0], "sum of the stages");
  EXPECT_EQ(table.rows[4][3], "162.5 %");
  EXPECT_EQ(table.rows[5][0], "wall time (the whole run)");
  EXPECT_EQ(table.rows[5][2], "4.000");
  EXPECT_NE(table.note.find("overlap"), std::string::npos) << table.note;
}

TEST(MapReportTest, TimingTableOnOneThreadSaysSo) {
  StageTimes t;
  t.imaging_s = 1.0;
  const ReportTable table = StageTimingTable(t, 2.0, false);
  EXPECT_EQ(table.rows[1][1], "feeding");
  EXPECT_EQ(table.note.find("overlap"), std::string::npos) << table.note;
  EXPECT_NE(table.note.find("one after"), std::string::npos) << table.note;
}

}  // namespace
}  // namespace uwbsar::slam

namespace uwbsar::slam {
namespace {

/// Pixels of `image` within `tolerance` of `colour` (anti-aliased edges count when close).
int PixelsOf(const cv::Mat& image, const cv::Scalar& colour, double tolerance = 10.0) {
  int n = 0;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      const cv::Vec3b v = image.at<cv::Vec3b>(r, c);
      n += cv::norm(cv::Scalar(v[0], v[1], v[2]) - colour) < tolerance;
    }
  }
  return n;
}

// On a straight run the SLAM path lies on the ground truth within a pixel and its loops join
// two passes at one place: the SLAM path, drawn last at the same width, hid the ground truth,
// and the loops (no length) did not show. Now SLAM is drawn wide first, the ground truth
// dashed on top, loops with a dot at each end, in the map figure and the trajectory plot.
TEST(MapReportTest, GroundTruthAndLoopsStayVisibleOnAStraightRun) {
  MapTrajectories t;
  for (int i = 0; i <= 200; ++i) {
    const double x = (i <= 100 ? i : 200 - i) * 0.02;  // out 2 m and back
    t.slam.push_back({i, Pose2{x, 0.0, 0.0}});
    t.ground_truth.push_back({i, Pose2{x, 0.0, 0.0}});
    t.odometry.push_back({i, Pose2{x, 0.002 * i, 0.0}});
  }
  const std::vector<FigurePath> paths = RunFigurePaths(t, 1);
  ASSERT_EQ(paths.size(), 3u);
  EXPECT_EQ(paths.front().label, "SLAM");
  EXPECT_EQ(paths.back().label, "ground truth");
  EXPECT_TRUE(paths.back().dashed);
  EXPECT_GT(paths.front().width, paths.back().width);

  MapFigure f;
  f.grid.resolution_m = 0.01;
  f.grid.cols = 300;
  f.grid.rows = 200;
  f.grid.x0_m = -0.5;
  f.grid.y0_m = 1.0;
  f.map_bgr = cv::Mat(f.grid.rows, f.grid.cols, CV_8UC3, kUnobservedBgr);
  f.colormap = "inferno";
  f.paths = paths;
  f.loops = {{{0.6, 0.0}, {0.6, 0.0}}, {{1.2, 0.0}, {1.2, 0.0}}};
  MapFigureLayout layout;
  const cv::Mat plot = RenderMapFigure(f, &layout)(layout.plot);
  EXPECT_GT(PixelsOf(plot, FigurePalette::kGroundTruth.bgr), 200);  // ~half of a 2 m dashed line
  EXPECT_GT(PixelsOf(plot, FigurePalette::kSlam.bgr), 100);         // beside and between dashes
  EXPECT_GT(PixelsOf(plot, FigurePalette::kLoop.bgr), 10);          // the two loops' dots

  RunReport report;
  report.trajectories = RunReportTrajectories(t);
  report.loop_segments = f.loops;
  const std::string html = RenderReportHtml(report);
  const std::size_t slam = html.find(std::string("stroke=\"") + FigurePalette::kSlam.css);
  const std::size_t truth = html.find(std::string("stroke=\"") + FigurePalette::kGroundTruth.css);
  ASSERT_NE(slam, std::string::npos);
  ASSERT_NE(truth, std::string::npos);
  EXPECT_LT(slam, truth);  // SVG paints in document order
  EXPECT_NE(html.find("stroke-dasharray", truth), std::string::npos);
  EXPECT_EQ(html.find("stroke-dasharray"), html.find("stroke-dasharray", truth));
  EXPECT_NE(html.find("class=\"loop-end\""), std::string::npos);
}

}  // namespace
}  // namespace uwbsar::slam
