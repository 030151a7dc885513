// Wall lines (frontend/wall_line.h): the straight walls of a tile come back as lines whose
// offset and normal match the walls' geometry to millimetres and a fraction of a degree, at any
// heading and for walls at a small angle to the path; noise gives no line, a wall with a step
// is refused rather than averaged, and the distance, count and order rules hold.
#include "frontend/wall_line.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "test/frontend/corridor_tile.h"

namespace uwbsar {
namespace {

using testing::CorridorTile;
using testing::SpeckledWalls;
using testing::TileGrid;
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

double AngleDiff(double a_rad, double b_rad) {
  return std::abs(std::remainder(a_rad - b_rad, 2.0 * kPi));
}

TEST(WallLineTest, StraightWallsAreMeasuredAtAnyHeadingAndAngle) {
  const WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  unsigned seed = 1;
  double worst_offset_m = 0.0, worst_normal_rad = 0.0;
  for (const double heading_deg : {0.0, 30.0, 90.0, -135.0}) {
    for (const double angle_deg : {-2.0, 0.0, 1.5}) {
      SCOPED_TRACE(::testing::Message() << "heading " << heading_deg << " angle " << angle_deg);
      const double h = heading_deg * kDeg, a = angle_deg * kDeg;
      // Walls 1.0 m left and 1.25 m right, turned by `a` about the anchor: their distances
      // along their own left normal h + a + 90 deg stay 1.0 and -1.25.
      const std::vector<WallLineObservation> lines =
          FindWallLines(CorridorTile(grid, h, {1.0, -1.25}, seed++, a), grid, h, config);
      ASSERT_EQ(lines.size(), 2u);
      EXPECT_GE(lines[0].contrast, lines[1].contrast);
      for (const WallLineObservation& line : lines) {
        const double truth_m = line.offset_m > 0.0 ? 1.0 : -1.25;
        EXPECT_NEAR(line.offset_m, truth_m, 0.005);
        EXPECT_LT(AngleDiff(line.normal_rad, h + a + 0.5 * kPi), 0.3 * kDeg);
        EXPECT_GT(line.normal_rad, -kPi);
        EXPECT_LE(line.normal_rad, kPi);
        EXPECT_LT(line.fit_rms_m, config.landmarks.max_fit_rms_m);
        EXPECT_GE(line.num_strips, config.landmarks.min_strips);
        // The walls are 2 m long around the anchor; the strips' centres lie within them.
        EXPECT_LT(line.begin_m, -0.4);
        EXPECT_GT(line.end_m, 0.4);
        EXPECT_GE(line.begin_m, -1.0);
        EXPECT_LE(line.end_m, 1.0);
        EXPECT_GE(line.offset_std_m, config.landmarks.offset_std_m);
        EXPECT_GE(line.normal_std_rad, config.landmarks.angle_std_deg * kDeg);
        worst_offset_m = std::max(worst_offset_m, std::abs(line.offset_m - truth_m));
        worst_normal_rad =
            std::max(worst_normal_rad, AngleDiff(line.normal_rad, h + a + 0.5 * kPi));
      }
    }
  }
  std::printf("worst offset error %.2f mm, worst normal error %.3f deg\n", 1e3 * worst_offset_m,
              worst_normal_rad / kDeg);
}

TEST(WallLineTest, FinePixelsGiveTheSameLines) {
  const WallProfileConfig config;
  // The 1 cm tile on 5 mm pixels (each pixel split in four of the same intensity), as the
  // imaging's 5 mm tiles are: about 1000 x 1000 pixels.
  const ImageGrid coarse = TileGrid();
  const ImageGrid grid = ImageGrid::Covering(-2.5, 2.5, -2.5, 2.5, 0.005);
  const double h = -50.0 * kDeg, a = 1.0 * kDeg;
  cv::Mat tile;
  cv::resize(CorridorTile(coarse, h, {0.8, -1.5}, 4, a), tile, cv::Size(grid.cols, grid.rows), 0, 0,
             cv::INTER_NEAREST);
  const std::vector<WallLineObservation> lines = FindWallLines(tile, grid, h, config);
  ASSERT_EQ(lines.size(), 2u);
  for (const WallLineObservation& line : lines) {
    EXPECT_NEAR(line.offset_m, line.offset_m > 0.0 ? 0.8 : -1.5, 0.005);
    EXPECT_LT(AngleDiff(line.normal_rad, h + a + 0.5 * kPi), 0.3 * kDeg);
  }
}

TEST(WallLineTest, NoiseAloneGivesNoLine) {
  const WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  for (unsigned seed = 1; seed <= 3; ++seed) {
    EXPECT_TRUE(FindWallLines(CorridorTile(grid, 0.3, {}, seed), grid, 0.3, config).empty());
  }
  EXPECT_TRUE(
      FindWallLines(cv::Mat::zeros(grid.rows, grid.cols, CV_32FC1), grid, 0.0, config).empty());
}

TEST(WallLineTest, AWallWithAStepIsRefusedNotAveraged) {
  const WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  for (const double heading_deg : {0.0, 30.0}) {
    SCOPED_TRACE(heading_deg);
    const double h = heading_deg * kDeg, ux = std::cos(h), uy = std::sin(h);
    // Left: 1.0 m away up to the anchor, then 10 cm further. Right: one straight wall.
    SpeckledWalls walls(grid, 7);
    walls.Add(ux, uy, 1.0, -1.0, 0.0);
    walls.Add(ux, uy, 1.1, 0.0, 1.0);
    walls.Add(ux, uy, -1.25, -1.0, 1.0);
    const std::vector<WallLineObservation> lines = FindWallLines(walls.tile(), grid, h, config);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NEAR(lines[0].offset_m, -1.25, 0.005);
    // The same tile with the step straightened out has both walls: the step was the reason.
    SpeckledWalls straight(grid, 7);
    straight.Add(ux, uy, 1.0, -1.0, 0.0);
    straight.Add(ux, uy, 1.0, 0.0, 1.0);
    straight.Add(ux, uy, -1.25, -1.0, 1.0);
    EXPECT_EQ(FindWallLines(straight.tile(), grid, h, config).size(), 2u);
  }
}

TEST(WallLineTest, AWallThatTurnsAwayKeepsOnlyItsStraightPart) {
  const WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  for (const double heading_deg : {0.0, 30.0, -135.0}) {
    SCOPED_TRACE(heading_deg);
    const double h = heading_deg * kDeg, ux = std::cos(h), uy = std::sin(h);
    // Left: 1.0 m away up to the anchor, then turning left by 90 deg (a side corridor's wall,
    // running away from the path 1.0..2.2 m across it at 0 along).
    SpeckledWalls walls(grid, 11);
    walls.Add(ux, uy, 1.0, -1.2, 0.0);
    walls.Add(-uy, ux, 0.0, 1.0, 2.2);
    walls.Add(ux, uy, -1.25, -1.2, 1.2);
    const std::vector<WallLineObservation> lines = FindWallLines(walls.tile(), grid, h, config);
    for (const WallLineObservation& line : lines) {
      EXPECT_LT(AngleDiff(line.normal_rad, h + 0.5 * kPi), 1.0 * kDeg);
      if (line.offset_m > 0.0) {
        // Where the side wall crosses the band (its outer half) it pulls the last strip out:
        // the offset is good to 2 cm there, not 5 mm.
        EXPECT_NEAR(line.offset_m, 1.0, 0.02);
        EXPECT_LT(line.end_m, 0.1);  // seen only where it runs along the path
      }
    }
    int right = 0;
    for (const WallLineObservation& line : lines) right += line.offset_m < 0.0;
    EXPECT_EQ(right, 1);
  }
}

TEST(WallLineTest, AWallNearerThanTheMinimumDistanceIsNotReturned) {
  WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  const cv::Mat tile = CorridorTile(grid, 0.5, {0.2, -1.25}, 5);
  const std::vector<WallLineObservation> lines = FindWallLines(tile, grid, 0.5, config);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NEAR(lines[0].offset_m, -1.25, 0.005);
  config.landmarks.min_distance_m = 0.1;
  EXPECT_EQ(FindWallLines(tile, grid, 0.5, config).size(), 2u);
}

TEST(WallLineTest, AtMostMaxLinesPerSideStrongestFirst) {
  WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  // Left: a wall at 1.6 m and a stronger one (drawn twice) at 1.0 m; right: one at 1.25 m.
  const cv::Mat tile = CorridorTile(grid, 0.2, {1.6, 1.0, 1.0, -1.25}, 9);
  std::vector<WallLineObservation> lines = FindWallLines(tile, grid, 0.2, config);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NEAR(lines[0].offset_m, 1.0, 0.005);
  EXPECT_NEAR(lines[1].offset_m, -1.25, 0.005);
  config.landmarks.max_lines_per_side = 2;
  lines = FindWallLines(tile, grid, 0.2, config);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_NEAR(lines[0].offset_m, 1.0, 0.005);
  EXPECT_GE(lines[0].contrast, lines[1].contrast);
  EXPECT_GE(lines[1].contrast, lines[2].contrast);
  int left = 0;
  for (const WallLineObservation& line : lines) left += line.offset_m > 0.0;
  EXPECT_EQ(left, 2);
  config.landmarks.max_lines_per_side = 0;
  EXPECT_TRUE(FindWallLines(tile, grid, 0.2, config).empty());
}

TEST(WallLineTest, WrongInputIsAnError) {
  const WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  EXPECT_THROW(FindWallLines(cv::Mat(3, 3, CV_32FC1, 0.0f), grid, 0.0, config),
               std::invalid_argument);
  EXPECT_THROW(FindWallLines(cv::Mat(grid.rows, grid.cols, CV_8UC1), grid, 0.0, config),
               std::invalid_argument);
}

}  // namespace
}  // namespace uwbsar
