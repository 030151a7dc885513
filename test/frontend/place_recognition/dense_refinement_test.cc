#include "frontend/place_recognition/dense_refinement.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test/frontend/place_recognition/texture.h"

namespace uwbsar {
namespace {

constexpr double kResolutionM = 0.01;

cv::Matx23d Rigid(const PixelRigid& t) {
  const double r = t.rotation_deg * M_PI / 180.0;
  return {std::cos(r), -std::sin(r), t.tx_px, std::sin(r), std::cos(r), t.ty_px};
}

/// Image b of the scene of `a` such that p_a = truth(p_b): b(p) = a(truth(p)); pixels that
/// fall outside a are not measured.
FeatureImage Seen(const FeatureImage& a, const PixelRigid& truth) {
  FeatureImage b;
  cv::warpAffine(a.gray, b.gray, cv::Mat(Rigid(truth)), a.gray.size(),
                 cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, 0);
  cv::warpAffine(a.mask, b.mask, cv::Mat(Rigid(truth)), a.mask.size(),
                 cv::INTER_NEAREST | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, 0);
  return b;
}

FeatureImage Textured(std::uint64_t seed) {
  FeatureImage f;
  f.gray = testing::BlobTexture(300, seed, 220);
  f.mask = cv::Mat(f.gray.size(), CV_8UC1, cv::Scalar(255));
  return f;
}

TEST(DenseRefinementTest, FindsTheTrueAlignmentFromAnOffSeedWithADistinctPeak) {
  const FeatureImage a = Textured(1);
  const PixelRigid truth{12.3, -7.6, 0.6};
  const FeatureImage b = Seen(a, truth);
  // Two detectors 6-8 px apart fuse to about this: 4 px and 0.5 deg off.
  const PixelRigid seed{truth.tx_px + 3.0, truth.ty_px - 2.5, truth.rotation_deg - 0.5};
  const DenseRefinementConfig config;
  const DenseRefinement r = RefineByCorrelation(a, b, seed, kResolutionM, config);
  ASSERT_TRUE(r.found) << r.reason;
  // The peak's transform maps b's centre where the truth does, within a pixel.
  const cv::Vec3d centre(150, 150, 1);
  const cv::Vec2d got = Rigid(r.transform) * centre, want = Rigid(truth) * centre;
  EXPECT_LT(cv::norm(got - want), 1.0);
  EXPECT_NEAR(r.transform.rotation_deg, truth.rotation_deg, 0.15);
  EXPECT_GT(r.peak_ncc, 0.8);
  EXPECT_GE(r.peak_ratio, config.min_peak_ratio);
  EXPECT_GE(r.peak_ncc, config.min_peak_ncc);
  EXPECT_GT(r.overlap_fraction, 0.8);
}

TEST(DenseRefinementTest, ImagesOfDifferentPlacesHaveNoStrongPeak) {
  const FeatureImage a = Textured(1), other = Textured(2);
  const DenseRefinementConfig config;
  const DenseRefinement r = RefineByCorrelation(a, other, {4.0, -3.0, 0.2}, kResolutionM, config);
  EXPECT_LT(r.peak_ncc, config.min_peak_ncc) << r.reason;
}

TEST(DenseRefinementTest, ALoneWallFitsAnywhereAlongItselfSoItsPeakIsNotDistinct) {
  FeatureImage wall;
  wall.gray = cv::Mat(300, 300, CV_8UC1, cv::Scalar(20));
  cv::line(wall.gray, {0, 140}, {299, 140}, cv::Scalar(250), 6);
  cv::GaussianBlur(wall.gray, wall.gray, cv::Size(), 2.0);
  wall.mask = cv::Mat(wall.gray.size(), CV_8UC1, cv::Scalar(255));
  const FeatureImage b = Seen(wall, {5.0, 2.0, 0.0});
  const DenseRefinement r =
      RefineByCorrelation(wall, b, {5.0, 2.0, 0.0}, kResolutionM, DenseRefinementConfig{});
  // A strong correlation, but along the wall as a ridge up to the window's edge.
  EXPECT_GT(r.peak_ncc, 0.5);
  EXPECT_LT(r.peak_ratio, DenseRefinementConfig{}.min_peak_ratio);
}

TEST(DenseRefinementTest, TooLittleOverlapIsRefused) {
  const FeatureImage a = Textured(1);
  const DenseRefinement r =
      RefineByCorrelation(a, a, {280.0, 0.0, 0.0}, kResolutionM, DenseRefinementConfig{});
  EXPECT_FALSE(r.found);
  EXPECT_EQ(r.reason, "too little overlap");
}

TEST(DenseRefinementTest, PackedImageKeepsTheMaskAndTheResult) {
  FeatureImage a = Textured(3);
  a.gray(cv::Rect(0, 0, 300, 40)).setTo(0);  // measured, but dark
  a.mask(cv::Rect(0, 0, 40, 300)).setTo(0);  // not measured
  const std::vector<unsigned char> packed = PackForRefinement(a);
  EXPECT_LT(packed.size(), a.gray.total());  // compressed
  const FeatureImage unpacked = UnpackForRefinement(packed);
  EXPECT_TRUE(unpacked.mask.empty());
  ASSERT_EQ(unpacked.gray.size(), a.gray.size());
  EXPECT_EQ(unpacked.gray.at<uchar>(10, 100), 1);  // measured zero stays measured
  EXPECT_EQ(unpacked.gray.at<uchar>(100, 10), 0);  // not measured
  EXPECT_EQ(unpacked.gray.at<uchar>(150, 150), std::max<uchar>(a.gray.at<uchar>(150, 150), 1));
  EXPECT_TRUE(UnpackForRefinement({}).gray.empty());
  EXPECT_TRUE(PackForRefinement(FeatureImage{}).empty());
  const PixelRigid truth{6.0, 3.0, 0.3};
  const FeatureImage b = Seen(a, truth);
  const DenseRefinement full =
      RefineByCorrelation(a, b, {8.0, 2.0, 0.0}, kResolutionM, DenseRefinementConfig{});
  const DenseRefinement from_packed =
      RefineByCorrelation(unpacked, UnpackForRefinement(PackForRefinement(b)), {8.0, 2.0, 0.0},
                          kResolutionM, DenseRefinementConfig{});
  ASSERT_TRUE(full.found && from_packed.found);
  EXPECT_NEAR(from_packed.transform.tx_px, full.transform.tx_px, 0.3);
  EXPECT_NEAR(from_packed.transform.ty_px, full.transform.ty_px, 0.3);
  EXPECT_NEAR(from_packed.peak_ncc, full.peak_ncc, 0.05);
}

}  // namespace
}  // namespace uwbsar
