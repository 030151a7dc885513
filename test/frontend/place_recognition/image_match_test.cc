// Matching two whole SAR images (`uwbsar match`): the transform's convention (a scatterer at
// p in A is at R(yaw) (p - c_A) + c_A + t in B, x to the right, y upwards, yaw
// counter-clockwise) checked on a textured image moved by a known amount.
#include "frontend/place_recognition/image_match.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

#include "slam/app_config.h"

namespace uwbsar {
namespace {

constexpr double kResolutionM = 0.005;

/// An enhanced (8-bit) image of bright blobs of several sizes on a dark background.
cv::Mat Texture(int rows, int cols, std::uint64_t seed = 7) {
  cv::Mat img(rows, cols, CV_8UC1, cv::Scalar(12));
  cv::RNG rng(seed);
  for (int k = 0; k < 260; ++k) {
    const cv::Point centre(rng.uniform(0, cols), rng.uniform(0, rows));
    cv::circle(img, centre, rng.uniform(2, 7), cv::Scalar(rng.uniform(60, 255)), cv::FILLED);
  }
  cv::GaussianBlur(img, img, cv::Size(), 2.0);
  return img;
}

SarImageFile Enhanced(const cv::Mat& image) {
  SarImageFile f;
  f.image = image;
  f.enhanced = true;
  f.grid.resolution_m = kResolutionM;
  f.grid.rows = image.rows;
  f.grid.cols = image.cols;
  f.observed = image > 0;
  return f;
}

/// B = A with every scatterer moved by R(yaw) (p - c) + c + (tx, ty), in metres, y up.
cv::Mat Moved(const cv::Mat& a, double tx_m, double ty_m, double yaw_deg) {
  const double c = std::cos(yaw_deg * M_PI / 180.0), s = std::sin(yaw_deg * M_PI / 180.0);
  const double ccol = 0.5 * (a.cols - 1), crow = 0.5 * (a.rows - 1);
  const double tx = tx_m / kResolutionM, ty = ty_m / kResolutionM;
  // In pixels (column, row), with y = -row: col' = c (col - cc) + s (row - cr) + cc + tx,
  // row' = -s (col - cc) + c (row - cr) + cr - ty.
  const cv::Matx23d M(c, s, ccol - c * ccol - s * crow + tx, -s, c,
                      crow + s * ccol - c * crow - ty);
  cv::Mat b;
  cv::warpAffine(a, b, M, a.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
  return b;
}

TEST(ImageMatchTest, KnownShiftAndRotationAreRecoveredInTheDocumentedConvention) {
  const Config config;
  const cv::Mat a = Texture(600, 600);
  const double tx = 0.06, ty = -0.04, yaw = 3.0;
  const SarImageFile fa = Enhanced(a), fb = Enhanced(Moved(a, tx, ty, yaw));
  const double feature_m = ImageFeatureResolution(kResolutionM, kResolutionM, config);
  const std::vector<DetectorKind> detectors = {DetectorKind::kAkaze, DetectorKind::kOrb};
  const ImageMatch m = MatchImages(ExtractImageFeatures(fa, detectors, config, feature_m),
                                   ExtractImageFeatures(fb, detectors, config, feature_m), config);
  ASSERT_TRUE(m.accepted()) << m.validation.reason;
  EXPECT_NEAR(m.transform.x_m, tx, 0.01);
  EXPECT_NEAR(m.transform.y_m, ty, 0.01);
  EXPECT_NEAR(m.transform.yaw_deg, yaw, 0.3);
  for (DetectorKind kind : detectors) {
    ASSERT_TRUE(m.detector_transforms.count(kind)) << DetectorName(kind);
    EXPECT_NEAR(m.detector_transforms.at(kind).x_m, tx, 0.015) << DetectorName(kind);
    EXPECT_NEAR(m.detector_transforms.at(kind).yaw_deg, yaw, 0.5) << DetectorName(kind);
  }
}

TEST(ImageMatchTest, UnrelatedImagesAreRejectedWithAReason) {
  const Config config;
  const cv::Mat a = Texture(600, 600);
  const cv::Mat b = Texture(600, 600, 8);  // the same statistics, another scene
  const double feature_m = ImageFeatureResolution(kResolutionM, kResolutionM, config);
  const std::vector<DetectorKind> detectors = {DetectorKind::kAkaze, DetectorKind::kOrb};
  const ImageMatch m =
      MatchImages(ExtractImageFeatures(Enhanced(a), detectors, config, feature_m),
                  ExtractImageFeatures(Enhanced(b), detectors, config, feature_m), config);
  EXPECT_FALSE(m.accepted());
  EXPECT_FALSE(m.validation.reason.empty());
}

TEST(ImageMatchTest, WithoutOrbTheRuleCannotBeApplied) {
  const Config config;
  const cv::Mat a = Texture(400, 400);
  const double feature_m = ImageFeatureResolution(kResolutionM, kResolutionM, config);
  const ImageFeatures f =
      ExtractImageFeatures(Enhanced(a), {DetectorKind::kAkaze}, config, feature_m);
  const ImageMatch m = MatchImages(f, f, config);
  EXPECT_FALSE(m.accepted());
  EXPECT_EQ(m.validation.reason, "AKAZE and ORB were not both run");
  EXPECT_EQ(m.matches.count(DetectorKind::kAkaze), 1u);
}

TEST(ImageMatchTest, CoarserImagesAreMatchedAtTheirOwnResolution) {
  Config config;
  EXPECT_DOUBLE_EQ(ImageFeatureResolution(0.005, 0.005, config), 0.01);
  EXPECT_DOUBLE_EQ(ImageFeatureResolution(0.005, 0.02, config), 0.02);
  config.place_recognition.detectors.feature_resolution_m = 0.0;
  EXPECT_DOUBLE_EQ(ImageFeatureResolution(0.005, 0.005, config), 0.005);
}

}  // namespace
}  // namespace uwbsar
