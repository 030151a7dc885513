#include "frontend/place_recognition/loop_validator.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <opencv2/calib3d.hpp>
#include <random>

namespace uwbsar {
namespace {

ImageGrid Grid(double x0, double y0) {
  ImageGrid g;
  g.x0_m = x0;
  g.y0_m = y0;
  g.resolution_m = 0.005;
  g.rows = 800;
  g.cols = 900;
  return g;
}

/// A match whose inliers are `points_j` (metres in frame j) seen in frame i through
/// T_ij, with pixel noise; the similarity is fitted like the matcher does.
MatchResult FakeMatch(DetectorKind kind, const ImageGrid& gi, const ImageGrid& gj,
                      const Pose2& T_ij, const std::vector<Point2>& points_j, double noise_px,
                      std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_px);
  MatchResult m;
  m.detector = kind;
  std::vector<cv::Point2f> pa, pb;
  for (const Point2& p : points_j) {
    const Point2 q = T_ij * p;
    const cv::Point2d a(gi.XToCol(q.x_m) + noise(rng), gi.YToRow(q.y_m) + noise(rng));
    const cv::Point2d b(gj.XToCol(p.x_m), gj.YToRow(p.y_m));
    m.inliers_a.push_back(a);
    m.inliers_b.push_back(b);
    pa.emplace_back(static_cast<float>(a.x), static_cast<float>(a.y));
    pb.emplace_back(static_cast<float>(b.x), static_cast<float>(b.y));
  }
  cv::Mat affine = cv::estimateAffinePartial2D(pb, pa, cv::noArray(), cv::LMEDS);
  affine.convertTo(affine, CV_64F);
  m.has_transform = true;
  m.good_matches = m.ratio_matches = static_cast<int>(points_j.size());
  m.scale = std::hypot(affine.at<double>(1, 0), affine.at<double>(0, 0));
  m.rotation_deg = std::atan2(affine.at<double>(1, 0), affine.at<double>(0, 0)) * 180 / M_PI;
  m.tx_px = affine.at<double>(0, 2);
  m.ty_px = affine.at<double>(1, 2);
  return m;
}

std::vector<Point2> Scatter(int n, std::uint64_t seed, double sx = 1.5, double sy = 1.5) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Point2> out;
  for (int k = 0; k < n; ++k) out.push_back({1.0 + sx * u(rng), 0.2 + sy * u(rng)});
  return out;
}

TEST(LoopValidatorTest, PixelTransformConvertsToTheExactMetricTransform) {
  const ImageGrid gi = Grid(-1.7, 3.2), gj = Grid(-2.3, 2.9);
  const Pose2 T_ij{1.23, -0.45, 0.2};
  // Pixel similarity of two points, then its metric counterpart.
  const Point2 p1{0.3, 0.4}, p2{1.5, -0.8};
  const Point2 q1 = T_ij * p1, q2 = T_ij * p2;
  const double rot =
      std::atan2(gi.YToRow(q2.y_m) - gi.YToRow(q1.y_m), gi.XToCol(q2.x_m) - gi.XToCol(q1.x_m)) -
      std::atan2(gj.YToRow(p2.y_m) - gj.YToRow(p1.y_m), gj.XToCol(p2.x_m) - gj.XToCol(p1.x_m));
  const double c = std::cos(rot), s = std::sin(rot);
  const double tx = gi.XToCol(q1.x_m) - (c * gj.XToCol(p1.x_m) - s * gj.YToRow(p1.y_m));
  const double ty = gi.YToRow(q1.y_m) - (s * gj.XToCol(p1.x_m) + c * gj.YToRow(p1.y_m));
  const Pose2 T = PixelToMetricTransform(gi, gj, tx, ty, rot * 180 / M_PI);
  EXPECT_NEAR(T.x_m, T_ij.x_m, 1e-9);
  EXPECT_NEAR(T.y_m, T_ij.y_m, 1e-9);
  EXPECT_NEAR(T.yaw_rad, T_ij.yaw_rad, 1e-9);
}

TEST(LoopValidatorTest, AcceptedLoopRecoversTheTransformWithAMatchDerivedInformation) {
  const ImageGrid gi = Grid(-1.7, 3.2), gj = Grid(-2.3, 2.9);
  const Pose2 T_ij{0.8, -0.3, 0.05};
  const MatchResult akaze = FakeMatch(DetectorKind::kAkaze, gi, gj, T_ij, Scatter(60, 1), 0.5, 2);
  const MatchResult orb = FakeMatch(DetectorKind::kOrb, gi, gj, T_ij, Scatter(40, 3), 0.5, 4);
  const LoopValidation v = ValidateLoop(3, gi, 17, gj, akaze, orb, LoopValidationConfig{});
  ASSERT_TRUE(v.accepted) << v.reason;
  const LoopConstraint& lc = v.constraint;
  EXPECT_EQ(lc.i, 3);
  EXPECT_EQ(lc.j, 17);
  EXPECT_NEAR(lc.T_ij.x_m, T_ij.x_m, 0.003);
  EXPECT_NEAR(lc.T_ij.y_m, T_ij.y_m, 0.003);
  EXPECT_NEAR(lc.T_ij.yaw_rad, T_ij.yaw_rad, 0.002);
  EXPECT_EQ(lc.good_matches.at(DetectorKind::kAkaze), 60);
  EXPECT_EQ(lc.good_matches.at(DetectorKind::kOrb), 40);
  // Symmetric positive definite, and no tighter than the configured floors.
  EXPECT_TRUE(lc.information.isApprox(lc.information.transpose()));
  const Eigen::Vector3d eig =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(lc.information).eigenvalues();
  EXPECT_GT(eig.minCoeff(), 0.0);
  EXPECT_LE(lc.information(0, 0), 1.0 / (0.005 * 0.005) + 1e-6);

  // More noise -> less information; more inliers -> more information.
  const MatchResult noisy_a = FakeMatch(DetectorKind::kAkaze, gi, gj, T_ij, Scatter(60, 1), 3.0, 2);
  const MatchResult noisy_o = FakeMatch(DetectorKind::kOrb, gi, gj, T_ij, Scatter(40, 3), 3.0, 4);
  const LoopValidation noisy = ValidateLoop(3, gi, 17, gj, noisy_a, noisy_o, {});
  ASSERT_TRUE(noisy.accepted) << noisy.reason;
  EXPECT_LT(noisy.constraint.information(0, 0), lc.information(0, 0));
  EXPECT_LT(noisy.constraint.information(2, 2), lc.information(2, 2));
  const MatchResult few_a = FakeMatch(DetectorKind::kAkaze, gi, gj, T_ij, Scatter(12, 5), 3.0, 2);
  const MatchResult few_o = FakeMatch(DetectorKind::kOrb, gi, gj, T_ij, Scatter(12, 6), 3.0, 4);
  const LoopValidation few = ValidateLoop(3, gi, 17, gj, few_a, few_o, {});
  ASSERT_TRUE(few.accepted) << few.reason;
  EXPECT_LT(few.constraint.information(0, 0), noisy.constraint.information(0, 0));
}

TEST(LoopValidatorTest, CollinearInliersAreRejectedAsDegenerate) {
  const ImageGrid gi = Grid(-1.7, 3.2), gj = Grid(-2.3, 2.9);
  const Pose2 T_ij{0.8, -0.3, 0.05};
  std::vector<Point2> line;
  for (int k = 0; k < 30; ++k) line.push_back({-0.5 + 0.05 * k, 1.2});  // along a wall
  const MatchResult a = FakeMatch(DetectorKind::kAkaze, gi, gj, T_ij, line, 0.0, 1);
  const MatchResult o = FakeMatch(DetectorKind::kOrb, gi, gj, T_ij, line, 0.0, 2);
  const LoopValidation v = ValidateLoop(0, gi, 1, gj, a, o, LoopValidationConfig{});
  EXPECT_FALSE(v.accepted);
  EXPECT_NE(v.reason.find("collinear"), std::string::npos) << v.reason;
  EXPECT_LT(v.inlier_spread_px, 1.0);
}

TEST(LoopValidatorTest, RuleRejectionIsPassedThrough) {
  const ImageGrid g = Grid(0, 0);
  const MatchResult a = FakeMatch(DetectorKind::kAkaze, g, g, {}, Scatter(8, 1), 0.2, 1);
  const MatchResult o = FakeMatch(DetectorKind::kOrb, g, g, {}, Scatter(40, 2), 0.2, 2);
  const LoopValidation v = ValidateLoop(0, g, 1, g, a, o, LoopValidationConfig{});
  EXPECT_FALSE(v.accepted);
  EXPECT_NE(v.reason.find("AKAZE: 8 good matches"), std::string::npos) << v.reason;
  EXPECT_TRUE(v.constraint.information.isZero());
}

}  // namespace
}  // namespace uwbsar
