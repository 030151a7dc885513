#include "frontend/place_recognition/feature_matcher.h"

#include <gtest/gtest.h>

#include "test/frontend/place_recognition/texture.h"

namespace uwbsar {
namespace {

FeatureSet Features(const cv::Mat& gray, DetectorKind kind) {
  return ComputeFeatures({gray, cv::Mat(gray.size(), CV_8U, cv::Scalar(255))}, kind,
                         DetectorConfig{});
}

TEST(FeatureMatcherTest, RecoversAShiftAndSmallRotationWithEveryDetector) {
  const cv::Mat a = testing::BlobTexture(500, 21, 220);
  const cv::Matx23d truth = testing::SimilarityAboutCentre(a.size(), -4.0, 1.0, {23.0, -17.0});
  const cv::Mat b = testing::Warp(a, truth);
  for (DetectorKind kind : AvailableDetectors()) {
    SCOPED_TRACE(DetectorName(kind));
    // Map b's pixels into a's: the inverse of `truth`.
    const MatchResult m = MatchFeatures(Features(a, kind), Features(b, kind), {});
    ASSERT_TRUE(m.has_transform) << m.reason;
    cv::Matx23d inverse;
    cv::invertAffineTransform(truth, inverse);
    const cv::Point2d p(250, 250);
    EXPECT_LT(cv::norm(testing::Apply(m.affine, p) - testing::Apply(inverse, p)), 1.0);
    EXPECT_NEAR(m.rotation_deg, -4.0, 0.5);  // the inverse turns back
    EXPECT_NEAR(m.scale, 1.0, 0.01);
    EXPECT_GT(m.good_matches, 20);
    EXPECT_LE(m.good_matches, m.ratio_matches);
    EXPECT_EQ(m.inliers_a.size(), static_cast<std::size_t>(m.good_matches));
    EXPECT_GE(m.match_ms, 0.0);
    EXPECT_TRUE(m.reason.empty());
  }
}

TEST(FeatureMatcherTest, UnrelatedTexturesGiveFewGoodMatches) {
  const FeatureSet a = Features(testing::BlobTexture(500, 31, 220), DetectorKind::kOrb);
  const FeatureSet b = Features(testing::BlobTexture(500, 32, 220), DetectorKind::kOrb);
  const MatchResult m = MatchFeatures(a, b, {});
  EXPECT_LT(m.good_matches, 10);
}

TEST(FeatureMatcherTest, TooFewKeypointsIsAReasonNotACrash) {
  const FeatureSet a = Features(testing::BlobTexture(500, 41, 220), DetectorKind::kAkaze);
  FeatureSet empty;
  empty.detector = DetectorKind::kAkaze;
  const MatchResult m = MatchFeatures(a, empty, {});
  EXPECT_FALSE(m.has_transform);
  EXPECT_NE(m.reason.find("fewer than 2 keypoints"), std::string::npos) << m.reason;
  EXPECT_EQ(m.good_matches, 0);
}

TEST(FeatureMatcherTest, RefusesToMatchDifferentDetectors) {
  const cv::Mat a = testing::BlobTexture(300, 42);
  const MatchResult m =
      MatchFeatures(Features(a, DetectorKind::kAkaze), Features(a, DetectorKind::kOrb), {});
  EXPECT_FALSE(m.has_transform);
  EXPECT_FALSE(m.reason.empty());
}

TEST(FeatureMatcherTest, RatioTestDropsAmbiguousMatches) {
  const cv::Mat a = testing::BlobTexture(400, 43, 200);
  const FeatureSet fa = Features(a, DetectorKind::kAkaze);
  FeatureMatchConfig strict;
  strict.ratio = 0.3;
  const MatchResult loose =
      MatchFeatures(fa, Features(testing::BlobTexture(400, 44, 200), DetectorKind::kAkaze), {});
  const MatchResult tight =
      MatchFeatures(fa, Features(testing::BlobTexture(400, 44, 200), DetectorKind::kAkaze), strict);
  EXPECT_LT(tight.ratio_matches, loose.ratio_matches);
}

}  // namespace
}  // namespace uwbsar
