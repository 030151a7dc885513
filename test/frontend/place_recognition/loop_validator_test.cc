#include "frontend/place_recognition/loop_validator.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <opencv2/calib3d.hpp>
#include <random>

#include "test/frontend/place_recognition/texture.h"

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

// Near agreements (validation.refinement): two detectors 12 px apart (limit 10 px, refined up
// to 1.5 x 10) on 1 cm images whose true transform lies between them.
struct NearAgreement {
  ImageGrid grid;
  FeatureImage a, b;
  cv::Matx23d truth{std::cos(0.4 * M_PI / 180), -std::sin(0.4 * M_PI / 180), 8.0,
                    std::sin(0.4 * M_PI / 180), std::cos(0.4 * M_PI / 180),  -5.0};

  explicit NearAgreement(std::uint64_t scene_b = 0) {
    grid = Grid(0, 3);
    grid.resolution_m = 0.01;
    grid.rows = grid.cols = 300;
    a.gray = testing::BlobTexture(300, 1, 220);
    a.mask = cv::Mat(a.gray.size(), CV_8UC1, cv::Scalar(255));
    // b sees a's scene through the truth (p_a = truth p_b), or another place.
    const cv::Mat scene = scene_b ? testing::BlobTexture(300, scene_b, 220) : a.gray;
    cv::warpAffine(scene, b.gray, cv::Mat(truth), a.gray.size(),
                   cv::INTER_LINEAR | cv::WARP_INVERSE_MAP);
    cv::warpAffine(a.mask, b.mask, cv::Mat(truth), a.gray.size(),
                   cv::INTER_NEAREST | cv::WARP_INVERSE_MAP);
  }
  /// A detector's match: the truth moved by (dx, dy) px, inliers on the truth.
  MatchResult Detector(DetectorKind kind, double dx, double dy, std::uint64_t seed) const {
    MatchResult m;
    m.detector = kind;
    m.has_transform = true;
    m.scale = 1.0;
    m.good_matches = m.ratio_matches = 30;
    m.rotation_deg = 0.4;
    m.tx_px = truth(0, 2) + dx;
    m.ty_px = truth(1, 2) + dy;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(30.0, 270.0);
    for (int k = 0; k < m.good_matches; ++k) {
      const cv::Vec3d pb(u(rng), u(rng), 1.0);
      const cv::Vec2d pa = truth * pb;
      m.inliers_b.emplace_back(pb[0], pb[1]);
      m.inliers_a.emplace_back(pa[0], pa[1]);
    }
    return m;
  }
  /// The refinement is off by default (its cost on long runs): these tests turn it on.
  static LoopValidationConfig Refining() {
    LoopValidationConfig c;
    c.refinement.enabled = true;
    return c;
  }
  LoopValidation Validate(double akaze_dx, double orb_dx, bool with_images = true,
                          LoopValidationConfig config = Refining()) const {
    return ValidateLoop(0, grid, 1, grid, Detector(DetectorKind::kAkaze, akaze_dx, 1.0, 1),
                        Detector(DetectorKind::kOrb, orb_dx, -1.0, 2), config,
                        with_images ? LoopImages{&a, &b} : LoopImages{});
  }
};

TEST(LoopValidatorTest, NearAgreementOfATruePairIsAcceptedAtTheCorrelationPeak) {
  const NearAgreement pair;
  const LoopValidation v = pair.Validate(+6.0, -6.0);
  ASSERT_TRUE(v.accepted) << v.reason;
  EXPECT_TRUE(v.refinement_tried && v.refined);
  EXPECT_GE(v.refinement.peak_ratio, LoopValidationConfig{}.refinement.min_peak_ratio);
  const Pose2 truth =
      PixelToMetricTransform(pair.grid, pair.grid, pair.truth(0, 2), pair.truth(1, 2), 0.4);
  EXPECT_NEAR(v.constraint.T_ij.x_m, truth.x_m, 0.01);
  EXPECT_NEAR(v.constraint.T_ij.y_m, truth.y_m, 0.01);
  EXPECT_NEAR(v.constraint.T_ij.yaw_rad, truth.yaw_rad, 0.003);
  EXPECT_TRUE(v.constraint.information.allFinite());
  // The paper's rule alone rejects it: without the images, or with the refinement off.
  const LoopValidation no_images = pair.Validate(+6.0, -6.0, false);
  EXPECT_FALSE(no_images.accepted);
  EXPECT_NE(no_images.reason.find("disagree"), std::string::npos) << no_images.reason;
  LoopValidationConfig off;
  off.refinement.enabled = false;
  EXPECT_FALSE(pair.Validate(+6.0, -6.0, true, off).accepted);
  // Far apart (beyond 1.5 x the limit) it is not tried, and callers need no images for it.
  EXPECT_FALSE(pair.Validate(+9.0, -9.0).refinement_tried);
  auto may_refine = [&](double akaze_dx, double orb_dx) {
    return MayRefine({{DetectorKind::kAkaze, pair.Detector(DetectorKind::kAkaze, akaze_dx, 1, 1)},
                      {DetectorKind::kOrb, pair.Detector(DetectorKind::kOrb, orb_dx, -1, 2)}},
                     NearAgreement::Refining());
  };
  EXPECT_TRUE(may_refine(+6.0, -6.0));
  EXPECT_FALSE(may_refine(+9.0, -9.0));  // far apart
  EXPECT_FALSE(may_refine(+2.0, -2.0));  // accepted by the rule
}

TEST(LoopValidatorTest, NearAgreementOnImagesOfDifferentPlacesIsRefused) {
  const LoopValidation v = NearAgreement(/*scene_b=*/7).Validate(+6.0, -6.0);
  EXPECT_TRUE(v.refinement_tried);
  EXPECT_FALSE(v.accepted);
  EXPECT_NE(v.reason.find("refinement:"), std::string::npos) << v.reason;
}

TEST(LoopValidatorTest, NearAgreementSeededAtAWrongTransformIsRefused) {
  // Both detectors 35-47 cm off the truth (seed 41 px off, the search reaches 6 px).
  const LoopValidation v = NearAgreement().Validate(+35.0, +47.0);
  EXPECT_TRUE(v.refinement_tried);
  EXPECT_FALSE(v.accepted) << v.reason;
}

TEST(LoopValidatorTest, NearAgreementWithOneDetectorOffThePeakIsRefused) {
  // ORB 1 px off the truth, AKAZE 11 px: the peak is near ORB's, AKAZE beyond the limit (10).
  const LoopValidation v = NearAgreement().Validate(+11.0, -1.0);
  EXPECT_TRUE(v.refinement_tried && v.refinement.found);
  EXPECT_FALSE(v.accepted);
  EXPECT_NE(v.reason.find("AKAZE off the correlation peak"), std::string::npos) << v.reason;
  std::printf("%s\n", v.reason.c_str());
}

}  // namespace
}  // namespace uwbsar
