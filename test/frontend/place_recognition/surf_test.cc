#include "frontend/place_recognition/surf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "frontend/place_recognition/feature_matcher.h"
#include "frontend/place_recognition/features.h"
#include "test/frontend/place_recognition/texture.h"

namespace uwbsar {
namespace {

using testing::Apply;
using testing::BlobTexture;
using testing::SimilarityAboutCentre;
using testing::Warp;

FeatureSet SurfFeatures(const cv::Mat& gray, int max_keypoints = 300, bool upright = false) {
  DetectorConfig config;
  config.max_keypoints = max_keypoints;
  config.surf_upright = upright;
  FeatureImage image{gray, cv::Mat(gray.size(), CV_8U, cv::Scalar(255))};
  return ComputeFeatures(image, DetectorKind::kSurf, config);
}

TEST(SurfTest, FindsABlobAtItsPositionAndScale) {
  cv::Mat img(200, 200, CV_32F, cv::Scalar(0));
  cv::circle(img, {97, 103}, 6, cv::Scalar(1.0), cv::FILLED);
  cv::GaussianBlur(img, img, cv::Size(0, 0), 2.0);
  cv::Mat gray;
  cv::normalize(img, gray, 0, 255, cv::NORM_MINMAX, CV_8U);
  const FeatureSet f = SurfFeatures(gray);
  ASSERT_GE(f.size(), 1);
  const cv::KeyPoint& best = f.keypoints[0];
  EXPECT_NEAR(best.pt.x, 97.0, 1.0);
  EXPECT_NEAR(best.pt.y, 103.0, 1.0);
  // A bright blob has a negative Laplacian (trace of the Hessian).
  EXPECT_EQ(best.class_id, -1);
  // Blob radius ~6.5 px after blur: the Hessian peaks at a filter side of ~ 2.5 r / 1.2 * 9 / 3.
  EXPECT_GT(best.size, 15.0f);
  EXPECT_LT(best.size, 60.0f);
}

TEST(SurfTest, DescriptorsAre64DimensionalUnitVectors) {
  const FeatureSet f = SurfFeatures(BlobTexture(400, 3));
  ASSERT_GT(f.size(), 50);
  EXPECT_EQ(f.descriptors.cols, 64);
  EXPECT_EQ(f.descriptors.type(), CV_32F);
  EXPECT_EQ(f.norm_type, cv::NORM_L2);
  for (int r = 0; r < f.descriptors.rows; ++r) {
    EXPECT_NEAR(cv::norm(f.descriptors.row(r)), 1.0, 1e-4);
  }
}

TEST(SurfTest, EmptyAndUniformImagesGiveNoKeypoints) {
  EXPECT_EQ(SurfFeatures(cv::Mat(300, 300, CV_8U, cv::Scalar(128))).size(), 0);
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  Surf::Create(SurfParams{})->detectAndCompute(cv::Mat(), cv::noArray(), kps, desc);
  EXPECT_TRUE(kps.empty());
  EXPECT_TRUE(desc.empty());
}

TEST(SurfTest, MaskRestrictsDetection) {
  const cv::Mat gray = BlobTexture(400, 5);
  std::vector<cv::KeyPoint> kps;
  cv::Mat mask(gray.size(), CV_8U, cv::Scalar(0));
  mask(cv::Rect(0, 0, 200, 400)).setTo(255);
  Surf::Create(SurfParams{})->detect(gray, kps, mask);
  ASSERT_FALSE(kps.empty());
  for (const cv::KeyPoint& k : kps) EXPECT_LT(k.pt.x, 200.5f);
}

/// Fraction of keypoints of `a` (whose warped position lies well inside b) that have a
/// keypoint of `b` within 2.5 px of it.
double Repeatability(const FeatureSet& a, const FeatureSet& b, const cv::Matx23d& m,
                     cv::Size size) {
  int visible = 0, repeated = 0;
  for (const cv::KeyPoint& k : a.keypoints) {
    const cv::Point2d p = Apply(m, k.pt);
    if (p.x < 20 || p.y < 20 || p.x > size.width - 20 || p.y > size.height - 20) continue;
    ++visible;
    for (const cv::KeyPoint& q : b.keypoints) {
      if (std::hypot(q.pt.x - p.x, q.pt.y - p.y) < 2.5) {
        ++repeated;
        break;
      }
    }
  }
  return visible > 0 ? static_cast<double>(repeated) / visible : 0.0;
}

struct WarpCase {
  double rotation_deg;
  double scale;
};

class SurfWarpTest : public ::testing::TestWithParam<WarpCase> {};

// The transform between a tile and its rotated / scaled copy is recovered
// within 1 px (at the image centre) and 1 deg; repeatability is printed.
TEST_P(SurfWarpTest, RecoversRotationAndScale) {
  const WarpCase c = GetParam();
  const cv::Mat a = BlobTexture(500, 11, 220);
  const cv::Matx23d truth = SimilarityAboutCentre(a.size(), c.rotation_deg, c.scale);
  const cv::Mat b = Warp(a, truth);
  const FeatureSet fa = SurfFeatures(a);
  const FeatureSet fb = SurfFeatures(b);
  // MatchFeatures(x, y) maps y's pixels into x's: match b against a to get a -> b.
  const MatchResult m = MatchFeatures(fb, fa, FeatureMatchConfig{});
  ASSERT_TRUE(m.has_transform) << m.reason;
  const cv::Point2d centre(249.5, 249.5);
  const double position_error = cv::norm(Apply(m.affine, centre) - Apply(truth, centre));
  // getRotationMatrix2D's positive angle is counter-clockwise on screen, i.e. negative
  // in the atan2 of the matrix (rows grow downwards).
  const double rotation_error = std::abs(std::remainder(m.rotation_deg + c.rotation_deg, 360.0));
  const double repeat = Repeatability(fa, fb, truth, b.size());
  std::printf(
      "[surf] rot %6.1f deg scale %.2f: %3d/%3d good, position error %.3f px, rotation "
      "error %.3f deg, scale %.4f, repeatability %.1f %%\n",
      c.rotation_deg, c.scale, m.good_matches, m.ratio_matches, position_error, rotation_error,
      m.scale, 100.0 * repeat);
  EXPECT_LT(position_error, 1.0);
  EXPECT_LT(rotation_error, 1.0);
  EXPECT_NEAR(m.scale, c.scale, 0.01);
  EXPECT_GT(m.good_matches, 20);
  EXPECT_GT(repeat, 0.3);
}

INSTANTIATE_TEST_SUITE_P(AcceptanceD, SurfWarpTest,
                         ::testing::Values(WarpCase{30, 1.0}, WarpCase{90, 1.0}, WarpCase{180, 1.0},
                                           WarpCase{0, 0.8}, WarpCase{0, 1.25}, WarpCase{30, 0.8}));

TEST(SurfTest, UprightMatchesShiftsButNotRotations) {
  const cv::Mat a = BlobTexture(500, 13, 220);
  const cv::Matx23d shift = SimilarityAboutCentre(a.size(), 0, 1.0, {12.0, -7.0});
  const MatchResult shifted = MatchFeatures(SurfFeatures(Warp(a, shift), 300, true),
                                            SurfFeatures(a, 300, true), FeatureMatchConfig{});
  ASSERT_TRUE(shifted.has_transform);
  EXPECT_NEAR(shifted.tx_px, 12.0, 0.5);
  EXPECT_NEAR(shifted.ty_px, -7.0, 0.5);
  const cv::Matx23d turn = SimilarityAboutCentre(a.size(), 90, 1.0);
  const MatchResult turned = MatchFeatures(SurfFeatures(Warp(a, turn), 300, true),
                                           SurfFeatures(a, 300, true), FeatureMatchConfig{});
  const MatchResult oriented =
      MatchFeatures(SurfFeatures(Warp(a, turn)), SurfFeatures(a), FeatureMatchConfig{});
  EXPECT_LT(turned.good_matches, oriented.good_matches / 3);
}

}  // namespace
}  // namespace uwbsar
