#include "imaging/enhance.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace uwbsar {

cv::Mat MagnitudeImage(const cv::Mat& sar) {
  cv::Mat mag;
  if (sar.channels() == 2) {
    std::vector<cv::Mat> parts;
    cv::split(sar, parts);
    cv::magnitude(parts[0], parts[1], mag);
  } else {
    mag = cv::abs(sar);
  }
  return mag;
}

cv::Mat PositiveImage(const cv::Mat& sar) {
  if (sar.channels() == 2) return MagnitudeImage(sar);
  cv::Mat positive;
  cv::max(sar, 0.0, positive);
  return positive * 2.0;  // Re(I) + |I|
}

cv::Mat EnhancedFloat(const cv::Mat& sar, const EnhanceConfig& config) {
  cv::Mat positive = PositiveImage(sar);
  if (config.blur_sigma_px <= 0.0) return positive;
  cv::Mat blurred;
  cv::GaussianBlur(positive, blurred, cv::Size(0, 0), config.blur_sigma_px, config.blur_sigma_px,
                   cv::BORDER_REPLICATE);
  return blurred;
}

cv::Mat Enhance8U(const cv::Mat& sar, const EnhanceConfig& config) {
  cv::Mat out;
  cv::normalize(EnhancedFloat(sar, config), out, 0, 255, cv::NORM_MINMAX, CV_8U);
  return out;
}

cv::Mat LogMagnitude8U(const cv::Mat& sar, double display_range_db) {
  cv::Mat mag = MagnitudeImage(sar);
  double max_value = 0.0;
  cv::minMaxLoc(mag, nullptr, &max_value);
  cv::Mat out(mag.size(), CV_8U, cv::Scalar(0));
  if (max_value <= 0.0) return out;
  cv::Mat db;
  cv::log(cv::max(mag / max_value, 1e-12), db);  // natural log
  db *= 20.0 / std::log(10.0);
  db.convertTo(out, CV_8U, 255.0 / display_range_db, 255.0);
  return out;
}

cv::Mat Colorize(const cv::Mat& gray8u, const std::string& colormap) {
  cv::Mat out;
  if (colormap == "gray") {
    cv::cvtColor(gray8u, out, cv::COLOR_GRAY2BGR);
    return out;
  }
  int map = cv::COLORMAP_INFERNO;
  if (colormap == "jet")
    map = cv::COLORMAP_JET;
  else if (colormap == "viridis")
    map = cv::COLORMAP_VIRIDIS;
  else if (colormap == "magma")
    map = cv::COLORMAP_MAGMA;
  else if (colormap == "hot")
    map = cv::COLORMAP_HOT;
  else if (colormap != "inferno")
    throw std::invalid_argument("unknown colour map " + colormap);
  cv::applyColorMap(gray8u, out, map);
  return out;
}

}  // namespace uwbsar
