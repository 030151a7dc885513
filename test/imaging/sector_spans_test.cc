#include "imaging/sector_spans.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace uwbsar {
namespace {

bool InsideSector(const Point2& p, const Pose2& T, const SectorShape& s) {
  const Point2 q = T.Inverse() * p;
  const double r = std::hypot(q.x_m, q.y_m);
  return r >= s.min_range_m && r <= s.max_range_m &&
         std::abs(std::atan2(q.y_m, q.x_m)) <= s.fov_half_angle_rad;
}

// Distance from p to the sector's boundary is tiny: membership may go either way.
bool NearBoundary(const Point2& p, const Pose2& T, const SectorShape& s) {
  const Point2 q = T.Inverse() * p;
  const double r = std::hypot(q.x_m, q.y_m);
  const double angle_margin =
      r * std::abs(std::abs(std::atan2(q.y_m, q.x_m)) - s.fov_half_angle_rad);
  return std::abs(r - s.min_range_m) < 1e-9 || std::abs(r - s.max_range_m) < 1e-9 ||
         angle_margin < 1e-9;
}

TEST(SectorSpansTest, SpansEqualBruteForceMembershipForRandomPoses) {
  const ImageGrid grid = ImageGrid::Covering(-4, 4, -4, 4, 0.02);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(-2.0, 2.0), yaw(-M_PI, M_PI), half(0.1, M_PI / 2);
  for (int trial = 0; trial < 40; ++trial) {
    const Pose2 T{pos(rng), pos(rng), yaw(rng)};
    const SectorShape sector{half(rng), 0.4, 3.0};
    std::vector<RowSpan> spans;
    const long long count = ComputeSectorSpans(grid, T, sector, &spans);
    std::vector<unsigned char> mask(grid.rows * grid.cols, 0);
    long long sum = 0;
    for (const RowSpan& s : spans) {
      ASSERT_GE(s.col_begin, 0);
      ASSERT_LE(s.col_end, grid.cols);
      for (int c = s.col_begin; c < s.col_end; ++c) {
        ASSERT_EQ(mask[s.row * grid.cols + c], 0) << "pixel listed twice";
        mask[s.row * grid.cols + c] = 1;
        ++sum;
      }
    }
    EXPECT_EQ(sum, count);
    int mismatches = 0;
    for (int r = 0; r < grid.rows; ++r) {
      for (int c = 0; c < grid.cols; ++c) {
        const Point2 p = grid.PixelToMetric(c, r);
        const bool inside = InsideSector(p, T, sector);
        if (inside != (mask[r * grid.cols + c] != 0) && !NearBoundary(p, T, sector)) ++mismatches;
      }
    }
    EXPECT_EQ(mismatches, 0) << "trial " << trial;
  }
}

TEST(SectorSpansTest, SectorOutsideImageGivesNoSpans) {
  const ImageGrid grid = ImageGrid::Covering(0, 1, 0, 1, 0.01);
  std::vector<RowSpan> spans;
  EXPECT_EQ(ComputeSectorSpans(grid, {10, 10, 0}, {0.5, 0.4, 3.0}, &spans), 0);
  EXPECT_TRUE(spans.empty());
}

TEST(SectorSpansTest, PixelCountMatchesSectorArea) {
  const ImageGrid grid = ImageGrid::Covering(-4, 4, -4, 4, 0.005);
  std::vector<RowSpan> spans;
  const SectorShape sector{M_PI / 6, 0.4, 3.0};
  const double pixels = double(ComputeSectorSpans(grid, {0.1, 0.2, 1.0}, sector, &spans));
  const double area = sector.fov_half_angle_rad * (9.0 - 0.16);  // 0.5 * 2 alpha * (R^2 - r^2)
  EXPECT_NEAR(pixels * 0.005 * 0.005, area, 0.002 * area);
}

}  // namespace
}  // namespace uwbsar
