#include "frontend/place_recognition/features.h"

#include <gtest/gtest.h>

#include <limits>

#include "test/frontend/place_recognition/texture.h"

namespace uwbsar {
namespace {

FeatureImage FullImage(const cv::Mat& gray) {
  return {gray, cv::Mat(gray.size(), CV_8U, cv::Scalar(255))};
}

TEST(FeaturesTest, EveryDetectorFindsAtMostMaxKeypointsWithItsNorm) {
  const FeatureImage image = FullImage(testing::BlobTexture(600, 1, 300));
  DetectorConfig config;
  for (DetectorKind kind : AvailableDetectors()) {
    const FeatureSet f = ComputeFeatures(image, kind, config);
    SCOPED_TRACE(DetectorName(kind));
    EXPECT_GT(f.size(), 50);
    EXPECT_LE(f.size(), config.max_keypoints);
    EXPECT_EQ(f.descriptors.rows, f.size());
    EXPECT_EQ(f.norm_type, MatchNorm(kind, config));
    for (int k = 1; k < f.size(); ++k) {
      EXPECT_GE(f.keypoints[k - 1].response, f.keypoints[k].response);
    }
  }
}

TEST(FeaturesTest, NormsFollowThePaper) {
  DetectorConfig c;
  EXPECT_EQ(MatchNorm(DetectorKind::kSift, c), cv::NORM_L2);
  EXPECT_EQ(MatchNorm(DetectorKind::kSurf, c), cv::NORM_L2);
  EXPECT_EQ(MatchNorm(DetectorKind::kAkaze, c), cv::NORM_L2);  // KAZE descriptor is float
  EXPECT_EQ(MatchNorm(DetectorKind::kBrisk, c), cv::NORM_HAMMING);
  EXPECT_EQ(MatchNorm(DetectorKind::kOrb, c), cv::NORM_HAMMING2);  // WTA_K = 4
  c.orb_wta_k = 2;
  EXPECT_EQ(MatchNorm(DetectorKind::kOrb, c), cv::NORM_HAMMING);
  const FeatureSet akaze = ComputeFeatures(FullImage(testing::BlobTexture(300, 2)),
                                           DetectorKind::kAkaze, DetectorConfig{});
  EXPECT_EQ(akaze.descriptors.type(), CV_32F);  // KAZE, not the binary MLDB
  EXPECT_EQ(akaze.descriptors.cols, 64);
}

TEST(FeaturesTest, MaxKeypointsKeepsTheStrongest) {
  const FeatureImage image = FullImage(testing::BlobTexture(600, 4, 300));
  DetectorConfig many, few;
  many.max_keypoints = 1000;
  few.max_keypoints = 20;
  const FeatureSet all = ComputeFeatures(image, DetectorKind::kAkaze, many);
  const FeatureSet top = ComputeFeatures(image, DetectorKind::kAkaze, few);
  ASSERT_EQ(top.size(), 20);
  ASSERT_GT(all.size(), 20);
  EXPECT_FLOAT_EQ(top.keypoints[0].response, all.keypoints[0].response);
  EXPECT_FLOAT_EQ(top.keypoints[19].response, all.keypoints[19].response);
}

TEST(FeaturesTest, ParsesDetectorNamesCaseInsensitively) {
  DetectorKind k;
  ASSERT_TRUE(ParseDetector("akaze", &k));
  EXPECT_EQ(k, DetectorKind::kAkaze);
  ASSERT_TRUE(ParseDetector("Orb", &k));
  EXPECT_EQ(k, DetectorKind::kOrb);
  EXPECT_FALSE(ParseDetector("harris", &k));
  EXPECT_STREQ(DetectorName(DetectorKind::kSurf), "SURF");
}

TEST(FeaturesTest, FeatureImageMasksUnimagedAndNonFinitePixels) {
  cv::Mat sar(100, 100, CV_32F, cv::Scalar(0));
  sar(cv::Rect(20, 20, 60, 60)).setTo(1.0);
  sar.at<float>(50, 50) = std::numeric_limits<float>::quiet_NaN();
  sar.at<float>(30, 30) = std::numeric_limits<float>::infinity();
  const FeatureImage f = MakeFeatureImage(sar, EnhanceConfig{}, 5);
  ASSERT_EQ(f.gray.type(), CV_8UC1);
  EXPECT_EQ(f.mask.at<uchar>(10, 10), 0);  // not imaged
  EXPECT_EQ(f.mask.at<uchar>(22, 50), 0);  // within 5 px of the edge
  EXPECT_EQ(f.mask.at<uchar>(40, 60), 255);
  EXPECT_EQ(f.mask.at<uchar>(52, 50), 0);  // next to the NaN
  EXPECT_GT(f.gray.at<uchar>(40, 60), 0);  // the Inf did not flatten the normalisation
}

TEST(FeaturesTest, CoherentTileUsesItsMagnitude) {
  cv::Mat sar(100, 100, CV_32FC2, cv::Scalar(0, 0));
  sar(cv::Rect(30, 30, 40, 40)).setTo(cv::Scalar(0.0, -2.0));  // negative imaginary part
  const FeatureImage f = MakeFeatureImage(sar, EnhanceConfig{}, 0);
  EXPECT_GT(f.gray.at<uchar>(50, 50), 200);
  EXPECT_EQ(f.mask.at<uchar>(50, 50), 255);
}

TEST(FeaturesTest, EmptyOrUniformTilesGiveNoFeatures) {
  for (DetectorKind kind : AvailableDetectors()) {
    SCOPED_TRACE(DetectorName(kind));
    EXPECT_EQ(ComputeFeatures(MakeFeatureImage(cv::Mat(), {}, 8), kind, {}).size(), 0);
    const cv::Mat uniform(200, 200, CV_32F, cv::Scalar(3.0));
    EXPECT_EQ(ComputeFeatures(MakeFeatureImage(uniform, {}, 8), kind, {}).size(), 0);
    const cv::Mat zeros(200, 200, CV_32F, cv::Scalar(0.0));
    EXPECT_EQ(ComputeFeatures(MakeFeatureImage(zeros, {}, 8), kind, {}).size(), 0);
  }
}

}  // namespace
}  // namespace uwbsar
