#include "eval/compare/sar_peaks.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/errors.h"
#include "imaging/enhance.h"
#include "imaging/image_header.h"

namespace uwbsar {

FloatSarMap LoadFloatSarMap(const std::string& tiff_path, const std::string& grid_yaml_path,
                            double max_image_pixels) {
  FloatSarMap map;
  map.grid = LoadSarGridMetadata(grid_yaml_path);
  std::error_code ec;  // a FIFO or a device is named by CheckImageSize
  if (!std::filesystem::exists(tiff_path, ec)) {
    throw InputError(tiff_path + ": float SAR map does not exist");
  }
  CheckImageSize(tiff_path, max_image_pixels, "float SAR map");
  std::vector<cv::Mat> pages;
  try {
    cv::imreadmulti(tiff_path, pages, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw InputError(tiff_path + ": cannot decode float SAR map: " + e.err);
  }
  if (pages.empty() || pages.size() > 2) {
    throw InputError(tiff_path + ": expected a float TIFF with 1 (real) or 2 (re, im) pages");
  }
  for (const cv::Mat& page : pages) {
    if (page.type() != CV_32FC1 || page.size() != pages[0].size()) {
      throw InputError(tiff_path + ": float SAR map pages must be single-channel 32-bit float " +
                       "images of one size");
    }
  }
  if (map.grid.rows > 0 && (pages[0].rows != map.grid.rows || pages[0].cols != map.grid.cols)) {
    throw InputError(tiff_path + ": image is " + std::to_string(pages[0].cols) + " x " +
                     std::to_string(pages[0].rows) + " pixels but " + grid_yaml_path + " says " +
                     std::to_string(map.grid.cols) + " x " + std::to_string(map.grid.rows));
  }
  map.grid.rows = pages[0].rows;
  map.grid.cols = pages[0].cols;
  if (pages.size() == 2) {
    cv::merge(pages, map.image);
  } else {
    map.image = pages[0];
  }
  return map;
}

std::vector<IntensityPoint> SarPeaks(const FloatSarMap& map, double min_fraction, double radius_m) {
  cv::Mat positive = PositiveImage(map.image);
  cv::patchNaNs(positive, 0.0);
  double max_value = 0.0;
  cv::minMaxLoc(positive, nullptr, &max_value);
  std::vector<IntensityPoint> peaks;
  if (!(max_value > 0.0)) return peaks;
  const int radius_px =
      std::max(1, static_cast<int>(std::lround(radius_m / map.grid.resolution_m)));
  cv::Mat local_max;
  cv::dilate(
      positive, local_max,
      cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius_px + 1, 2 * radius_px + 1)));
  const float threshold = static_cast<float>(min_fraction * max_value);
  for (int r = 0; r < positive.rows; ++r) {
    const float* v = positive.ptr<float>(r);
    const float* m = local_max.ptr<float>(r);
    for (int c = 0; c < positive.cols; ++c) {
      if (v[c] > 0.0f && v[c] >= threshold && v[c] >= m[c]) {
        peaks.push_back({map.grid.x0_m + c * map.grid.resolution_m,
                         map.grid.y0_m - r * map.grid.resolution_m, v[c]});
      }
    }
  }
  return peaks;
}

}  // namespace uwbsar
