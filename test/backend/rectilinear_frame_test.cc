// FitRectilinearFrame (backend/rectilinear_frame.h): the frame of a square building's walls is
// found whatever quarter turn each wall faces, and the walls' spread about it tells a square
// building from one whose corners are 2 deg off.
#include "backend/rectilinear_frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace uwbsar {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(RectilinearFrameTest, ASquareBuildingsWallsShareOneFrameWhicheverWayTheyFace) {
  // Walls 10 deg off the axes, facing all four ways, with half a degree of error on some.
  const std::vector<double> normals = {10 * kDeg, 100.5 * kDeg, 190 * kDeg, -80.5 * kDeg,
                                       -170 * kDeg};
  const RectilinearFit fit = FitRectilinearFrame(normals, {1, 1, 1, 1, 1});
  EXPECT_NEAR(fit.frame_rad, 10 * kDeg, 0.01 * kDeg);
  EXPECT_NEAR(fit.rms_rad, std::sqrt(2 * 0.5 * 0.5 / 5) * kDeg, 0.01 * kDeg);
  EXPECT_DOUBLE_EQ(fit.weight, 5.0);
}

TEST(RectilinearFrameTest, WallsOfABuildingTwoDegreesOffSquareSpreadByOneDegree) {
  // x along 0 deg, y walls along 88 deg (a parallelogram): normals 90 and -2 (mod 90: 0, -2).
  const RectilinearFit fit =
      FitRectilinearFrame({90 * kDeg, -2 * kDeg, -90 * kDeg, 178 * kDeg}, {3, 3, 3, 3});
  EXPECT_NEAR(fit.frame_rad, -1 * kDeg, 0.01 * kDeg);
  EXPECT_NEAR(fit.rms_rad, 1 * kDeg, 0.01 * kDeg);
  // Weights: a long wall counts for more than a short one.
  const RectilinearFit weighted = FitRectilinearFrame({90 * kDeg, -2 * kDeg}, {3, 1});
  EXPECT_NEAR(weighted.frame_rad, -0.5 * kDeg, 0.02 * kDeg);
}

TEST(RectilinearFrameTest, NoWallsFitNothing) {
  const RectilinearFit fit = FitRectilinearFrame({}, {});
  EXPECT_EQ(fit.weight, 0.0);
  EXPECT_EQ(fit.rms_rad, 0.0);
  const RectilinearFit zero = FitRectilinearFrame({0.3}, {0.0});
  EXPECT_EQ(zero.weight, 0.0);
}

}  // namespace
}  // namespace uwbsar
