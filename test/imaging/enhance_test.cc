#include "imaging/enhance.h"

#include <gtest/gtest.h>

namespace uwbsar {
namespace {

TEST(EnhanceTest, PositiveImageIsRealPlusAbsolute) {
  cv::Mat img = (cv::Mat_<float>(1, 4) << -2.0f, 0.0f, 1.5f, -0.1f);
  cv::Mat pos = PositiveImage(img);
  EXPECT_FLOAT_EQ(pos.at<float>(0, 0), 0.0f);
  EXPECT_FLOAT_EQ(pos.at<float>(0, 2), 3.0f);
  EXPECT_FLOAT_EQ(pos.at<float>(0, 3), 0.0f);
}

TEST(EnhanceTest, EnhancedEightBitSpansFullRange) {
  cv::Mat img(50, 50, CV_32F, cv::Scalar(0));
  img.at<float>(25, 25) = 10.0f;
  img.at<float>(10, 10) = -5.0f;
  const cv::Mat e = Enhance8U(img, EnhanceConfig{});
  double lo, hi;
  cv::minMaxLoc(e, &lo, &hi);
  EXPECT_EQ(lo, 0.0);
  EXPECT_EQ(hi, 255.0);
  EXPECT_EQ(e.at<unsigned char>(25, 25), 255);
  // Blurred with sigma 2: the neighbour two pixels away keeps exp(-1/2) of the peak.
  EXPECT_NEAR(e.at<unsigned char>(25, 27), 255 * std::exp(-0.5), 3);
}

TEST(EnhanceTest, LogMagnitudeMapsDisplayRange) {
  cv::Mat img(1, 3, CV_32FC2);
  img.at<cv::Vec2f>(0, 0) = {3.0f, 4.0f};     // |5|: the peak -> 255
  img.at<cv::Vec2f>(0, 1) = {0.5f, 0.0f};     // -20 dB -> 255 * (1 - 20/30)
  img.at<cv::Vec2f>(0, 2) = {0.0f, 0.0001f};  // below the range -> 0
  const cv::Mat d = LogMagnitude8U(img, 30.0);
  EXPECT_EQ(d.at<unsigned char>(0, 0), 255);
  EXPECT_NEAR(d.at<unsigned char>(0, 1), 85, 1);
  EXPECT_EQ(d.at<unsigned char>(0, 2), 0);
}

TEST(EnhanceTest, ColorizeGivesThreeChannels) {
  cv::Mat g(4, 4, CV_8U, cv::Scalar(128));
  EXPECT_EQ(Colorize(g, "inferno").type(), CV_8UC3);
  EXPECT_EQ(Colorize(g, "gray").type(), CV_8UC3);
  EXPECT_THROW(Colorize(g, "rainbow"), std::invalid_argument);
}

}  // namespace
}  // namespace uwbsar
