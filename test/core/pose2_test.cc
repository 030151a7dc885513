#include "core/pose2.h"

#include <gtest/gtest.h>

namespace uwbsar {
namespace {

TEST(Pose2Test, ComposeWithInverseIsIdentity) {
  const Pose2 a{1.5, -2.0, 2.9};
  const Pose2 id = a * a.Inverse();
  EXPECT_NEAR(id.x_m, 0.0, 1e-12);
  EXPECT_NEAR(id.y_m, 0.0, 1e-12);
  EXPECT_NEAR(id.yaw_rad, 0.0, 1e-12);
}

TEST(Pose2Test, BetweenRecoversRelativePose) {
  const Pose2 w_a{1.0, 2.0, 0.5};
  const Pose2 a_b{0.3, -0.7, -2.0};
  const Pose2 rel = Between(w_a, w_a * a_b);
  EXPECT_NEAR(rel.x_m, a_b.x_m, 1e-12);
  EXPECT_NEAR(rel.y_m, a_b.y_m, 1e-12);
  EXPECT_NEAR(rel.yaw_rad, a_b.yaw_rad, 1e-12);
}

TEST(Pose2Test, TransformsPointsIntoParentFrame) {
  const Pose2 T{1.0, 0.0, M_PI / 2};
  const Point2 p = T * Point2{1.0, 0.0};
  EXPECT_NEAR(p.x_m, 1.0, 1e-12);
  EXPECT_NEAR(p.y_m, 1.0, 1e-12);
}

TEST(Pose2Test, NormalizeAngleWrapsIntoHalfOpenInterval) {
  EXPECT_NEAR(NormalizeAngle(3 * M_PI), -M_PI, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-0.5), -0.5, 1e-12);
  EXPECT_NEAR(NormalizeAngle(7.0), 7.0 - 2 * M_PI, 1e-12);
}

TEST(Pose2Test, InterpolateTakesShortestArc) {
  const Pose2 a{0, 0, M_PI - 0.1};
  const Pose2 b{2, 0, -M_PI + 0.1};
  const Pose2 mid = Interpolate(a, b, 0.5);
  EXPECT_NEAR(mid.x_m, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(mid.yaw_rad), M_PI, 1e-9);
}

}  // namespace
}  // namespace uwbsar
