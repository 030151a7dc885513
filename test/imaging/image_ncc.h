// Zero-mean normalised cross-correlation of two images: how alike two SAR images are up to gain
// and offset (1 = equal so, 0 = unrelated). The figure the imaging comparisons of the tests and
// benchmarks quote (ffbp against direct, the simulator against real strips); the product has no
// use for it.
#pragma once

#include <cmath>
#include <opencv2/core.hpp>

namespace uwbsar {

/// `a` and `b` are one-channel images of one size, any depth; 0 when either is uniform.
inline double ZeroMeanNcc(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat fa, fb;
  a.convertTo(fa, CV_64F);
  b.convertTo(fb, CV_64F);
  fa -= cv::mean(fa)[0];
  fb -= cv::mean(fb)[0];
  const double den = std::sqrt(fa.dot(fa) * fb.dot(fb));
  return den > 0.0 ? fa.dot(fb) / den : 0.0;
}

}  // namespace uwbsar
