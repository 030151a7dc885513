// Test helper: a SAR-like 8-bit texture (bright blobs of several sizes and short
// bright segments on a dark, slightly noisy background) and exact warps of it, for
// detector and matcher tests that must run in milliseconds.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

namespace uwbsar::testing {

inline cv::Mat BlobTexture(int size_px, std::uint64_t seed, int blobs = 140) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  cv::Mat img(size_px, size_px, CV_32F, cv::Scalar(0));
  for (int k = 0; k < blobs; ++k) {
    const cv::Point c(static_cast<int>(u(rng) * size_px), static_cast<int>(u(rng) * size_px));
    const double amp = 0.3 + 0.7 * u(rng);
    if (u(rng) < 0.75) {
      cv::circle(img, c, 1 + static_cast<int>(6 * u(rng)), cv::Scalar(amp), cv::FILLED);
    } else {
      const double a = u(rng) * CV_PI;
      const double len = 8 + 25 * u(rng);
      cv::line(
          img, c,
          c + cv::Point(static_cast<int>(len * std::cos(a)), static_cast<int>(len * std::sin(a))),
          cv::Scalar(amp), 2);
    }
  }
  cv::GaussianBlur(img, img, cv::Size(0, 0), 2.0);
  cv::Mat noise(img.size(), CV_32F);
  cv::randn(noise, 0.0, 0.01);
  img += noise;
  cv::Mat out;
  cv::normalize(img, out, 0, 255, cv::NORM_MINMAX, CV_8U);
  return out;
}

/// The similarity mapping a point of `src` to the warped image: rotation by `deg`
/// (counter-clockwise on screen is negative in pixel coordinates; OpenCV convention)
/// about the image centre, then scaling, then a shift.
inline cv::Matx23d SimilarityAboutCentre(cv::Size size, double deg, double scale,
                                         cv::Point2d shift = {0, 0}) {
  const cv::Point2f centre(0.5f * static_cast<float>(size.width - 1),
                           0.5f * static_cast<float>(size.height - 1));
  cv::Mat m = cv::getRotationMatrix2D(centre, deg, scale);
  cv::Matx23d out;
  m.convertTo(m, CV_64F);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = m.at<double>(r, c);
  out(0, 2) += shift.x;
  out(1, 2) += shift.y;
  return out;
}

inline cv::Mat Warp(const cv::Mat& src, const cv::Matx23d& m) {
  cv::Mat out;
  cv::warpAffine(src, out, cv::Mat(m), src.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
                 cv::Scalar(0));
  return out;
}

inline cv::Point2d Apply(const cv::Matx23d& m, cv::Point2d p) {
  return {m(0, 0) * p.x + m(0, 1) * p.y + m(0, 2), m(1, 0) * p.x + m(1, 1) * p.y + m(1, 2)};
}

}  // namespace uwbsar::testing
