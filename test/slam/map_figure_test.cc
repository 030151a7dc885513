// slam/outputs/map_figure.h: the report's annotated map figure frames map.png's raster with axes,
// a scale bar, a colour bar and a legend in distinct colours, and draws loops above paths.
#include "slam/outputs/map_figure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "imaging/enhance.h"

namespace uwbsar::slam {
namespace {

/// A 3 m x 2 m raster at 1 cm of one flat colour, the unobserved grey.
MapFigure FlatFigure() {
  MapFigure f;
  f.grid.resolution_m = 0.01;
  f.grid.cols = 300;
  f.grid.rows = 200;
  f.grid.x0_m = -1.0;
  f.grid.y0_m = 0.5;
  f.map_bgr = cv::Mat(f.grid.rows, f.grid.cols, CV_8UC3, kUnobservedBgr);
  f.colormap = "inferno";
  return f;
}

int NonWhite(const cv::Mat& region) {
  cv::Mat gray;
  cv::cvtColor(region, gray, cv::COLOR_BGR2GRAY);
  return cv::countNonZero(gray < 250);
}

bool Same(const cv::Vec3b& a, const cv::Scalar& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

TEST(MapFigureTest, FramesTheRasterWithLabelledAxesInTheMargins) {
  const MapFigure f = FlatFigure();
  MapFigureLayout layout;
  const cv::Mat figure = RenderMapFigure(f, &layout);
  EXPECT_EQ(layout.plot.size(), f.map_bgr.size());
  EXPECT_GT(figure.cols, f.map_bgr.cols + layout.plot.x);  // a left margin and the panel
  EXPECT_GT(figure.rows, f.map_bgr.rows + layout.plot.y);  // a top and a bottom margin
  // Without paths the plot is the raster itself.
  EXPECT_EQ(cv::norm(figure(layout.plot), f.map_bgr, cv::NORM_INF), 0.0);
  // Tick labels left of the plot (y) and under it (x); the margins are white elsewhere.
  const cv::Rect left_margin(0, layout.plot.y, layout.plot.x - 2, layout.plot.height);
  const cv::Rect bottom_margin(layout.plot.x, layout.plot.br().y + 2, layout.plot.width,
                               figure.rows - layout.plot.br().y - 2);
  EXPECT_GT(NonWhite(figure(left_margin)), 20);
  EXPECT_GT(NonWhite(figure(bottom_margin)), 20);
  EXPECT_EQ(figure.at<cv::Vec3b>(0, figure.cols - 1), cv::Vec3b(255, 255, 255));
  // 3 m wide: ticks every 0.5 m, a scale bar of 0.5 m (a fifth of the width at most).
  EXPECT_DOUBLE_EQ(layout.tick_step_m, 0.5);
  EXPECT_DOUBLE_EQ(layout.scale_bar_m, 0.5);
}

TEST(MapFigureTest, LegendEntriesHaveDistinctPaletteColours) {
  MapFigure f = FlatFigure();
  f.paths.push_back({"ground truth", FigurePalette::kGroundTruth, {{-0.5, 0.0}, {1.0, 0.0}}});
  f.paths.push_back({"odometry", FigurePalette::kOdometry, {{-0.5, -0.5}, {1.0, -0.5}}});
  f.paths.push_back({"SLAM", FigurePalette::kSlam, {{-0.5, -1.0}, {1.0, -1.0}}});
  f.loops.push_back({{0.0, 0.0}, {0.0, -1.0}});
  MapFigureLayout layout;
  const cv::Mat figure = RenderMapFigure(f, &layout);
  ASSERT_EQ(layout.legend_swatches.size(), 4u);
  const cv::Scalar expected[] = {FigurePalette::kGroundTruth.bgr, FigurePalette::kOdometry.bgr,
                                 FigurePalette::kSlam.bgr, FigurePalette::kLoop.bgr};
  for (std::size_t i = 0; i < 4; ++i) {
    const cv::Vec3b at = figure.at<cv::Vec3b>(layout.legend_swatches[i]);
    EXPECT_TRUE(Same(at, expected[i])) << i << ": " << at;
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_NE(at, figure.at<cv::Vec3b>(layout.legend_swatches[j])) << i << " vs " << j;
    }
  }
}

TEST(MapFigureTest, LoopsAreDrawnAbovePathsAndMarkersMarkStartAndEnd) {
  MapFigure f = FlatFigure();
  f.paths.push_back({"SLAM", FigurePalette::kSlam, {{-0.8, -0.5}, {1.5, -0.5}}});
  f.loops.push_back({{0.5, 0.3}, {0.5, -1.2}});
  MapFigureLayout layout;
  const cv::Mat figure = RenderMapFigure(f, &layout);
  auto at = [&](double x, double y) {
    return figure.at<cv::Vec3b>(layout.plot.y + static_cast<int>(std::lround(f.grid.YToRow(y))),
                                layout.plot.x + static_cast<int>(std::lround(f.grid.XToCol(x))));
  };
  // The crossing is the loop's colour (anti-aliased: nearly), not the path's.
  const cv::Vec3b crossing = at(0.5, -0.5);
  const cv::Scalar crossing_bgr(crossing[0], crossing[1], crossing[2]);
  EXPECT_LT(cv::norm(crossing_bgr - FigurePalette::kLoop.bgr), 40.0) << crossing;
  EXPECT_GT(cv::norm(crossing_bgr - FigurePalette::kSlam.bgr), 100.0) << crossing;
  EXPECT_TRUE(Same(at(0.0, -0.5), FigurePalette::kSlam.bgr));
  // The start marker is wider than the path: filled in the path's colour off its line.
  EXPECT_TRUE(Same(at(-0.8, -0.5 + 0.03), FigurePalette::kSlam.bgr)) << at(-0.8, -0.47);
  EXPECT_FALSE(Same(at(0.0, -0.5 + 0.03), FigurePalette::kSlam.bgr));
}

TEST(MapFigureTest, ColourBarRunsFromTheColormapsTopToItsBottom) {
  const MapFigure f = FlatFigure();
  MapFigureLayout layout;
  const cv::Mat figure = RenderMapFigure(f, &layout);
  const cv::Mat ends = Colorize((cv::Mat_<unsigned char>(2, 1) << 255, 0), "inferno");
  const cv::Rect& bar = layout.colour_bar;
  ASSERT_GT(bar.height, 10);
  const cv::Point centre_top(bar.x + bar.width / 2, bar.y);
  const cv::Point centre_bottom(bar.x + bar.width / 2, bar.br().y - 1);
  EXPECT_EQ(figure.at<cv::Vec3b>(centre_top), ends.at<cv::Vec3b>(0));
  EXPECT_EQ(figure.at<cv::Vec3b>(centre_bottom), ends.at<cv::Vec3b>(1));
}

TEST(MapFigureTest, PaletteTellsTrajectoriesAndLoopsApart) {
  const FigureColour colours[] = {FigurePalette::kSlam, FigurePalette::kOdometry,
                                  FigurePalette::kGroundTruth, FigurePalette::kLoop};
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_GT(cv::norm(colours[i].bgr - colours[j].bgr), 60.0) << colours[i].name;
      EXPECT_STRNE(colours[i].css, colours[j].css);
    }
  }
  for (std::size_t n = 0; n < 6; ++n) {
    EXPECT_STRNE(FigurePalette::Run(n).css, FigurePalette::kLoop.css) << n;
    if (n > 0) {
      EXPECT_STRNE(FigurePalette::Run(n).css, FigurePalette::Run(n - 1).css) << n;
    }
  }
}

TEST(MapFigureTest, ScaledMapPutsThePercentileAtTheTopAndGreysTheUnobserved) {
  cv::Mat map(10, 100, CV_32FC1);
  for (int c = 0; c < 100; ++c) map.col(c).setTo(static_cast<float>(c + 1));
  cv::Mat observed(10, 100, CV_8UC1, cv::Scalar(255));
  observed.col(0).setTo(0);
  float top = 0.0f;
  const cv::Mat image = ScaledMapImage(map, observed, "gray", &top);
  EXPECT_NEAR(top, 100.0f, 1.0f);  // the 99.5th percentile of 2 .. 100
  EXPECT_TRUE(Same(image.at<cv::Vec3b>(0, 0), kUnobservedBgr));
  EXPECT_EQ(image.at<cv::Vec3b>(0, 99)[0], 255);
  EXPECT_LT(image.at<cv::Vec3b>(0, 49)[0], 140);
}

TEST(MapFigureTest, NiceStepsAreOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(NiceStep(10.0, 5.0), 2.0);
  EXPECT_DOUBLE_EQ(NiceStep(3.0, 6.0), 0.5);
  EXPECT_NEAR(NiceStep(0.07, 7.0), 0.01, 1e-12);
  EXPECT_DOUBLE_EQ(NiceStep(40.0, 6.0), 5.0);
}

}  // namespace
}  // namespace uwbsar::slam
