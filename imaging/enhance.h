// Image enhancement (paper section "UWB SAR Imaging"): positive image
// Re(I) + |I| = 2 max(I, 0), Gaussian blur (sigma 2 px), min-max to 8 bit;
// and magnitude / log-magnitude display for coherent (complex) images.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "imaging/enhance_config.h"

namespace uwbsar {

/// Paper mode: Re(I) + |I| for a real image; for a complex image, its magnitude.
cv::Mat PositiveImage(const cv::Mat& sar);
/// |I| for complex images, |I| of the real image otherwise (CV_32FC1).
cv::Mat MagnitudeImage(const cv::Mat& sar);
/// The paper's feature image as float: positive image blurred with sigma (no normalisation).
cv::Mat EnhancedFloat(const cv::Mat& sar, const EnhanceConfig& config);
/// The paper's 8-bit feature image: EnhancedFloat, then min-max normalised to 0..255.
cv::Mat Enhance8U(const cv::Mat& sar, const EnhanceConfig& config);
/// Log-magnitude display: 0 at peak - display_range_db, 255 at the peak.
cv::Mat LogMagnitude8U(const cv::Mat& sar, double display_range_db);
/// Applies the configured colour map (gray returns a 3-channel gray image).
cv::Mat Colorize(const cv::Mat& gray8u, const std::string& colormap);

}  // namespace uwbsar
