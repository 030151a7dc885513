#include "frontend/place_recognition/features.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "imaging/enhance.h"

#ifdef UWBSAR_WITH_SURF
#include "frontend/place_recognition/surf.h"
#endif

namespace uwbsar {

cv::Ptr<cv::Feature2D> CreateDetector(DetectorKind kind, const DetectorConfig& c) {
  switch (kind) {
    case DetectorKind::kSift:
      return cv::SIFT::create(c.max_keypoints, 3, c.sift_contrast_threshold);
    case DetectorKind::kSurf: {
#ifdef UWBSAR_WITH_SURF
      SurfParams p;
      p.hessian_threshold = c.surf_hessian_threshold;
      p.octaves = c.surf_octaves;
      p.octave_layers = c.surf_octave_layers;
      p.upright = c.surf_upright;
      p.max_keypoints = c.max_keypoints;
      return Surf::Create(p);
#else
      CV_Error(cv::Error::StsNotImplemented, "SURF needs -DUWBSAR_WITH_SURF=ON");
#endif
    }
    case DetectorKind::kBrisk:
      return cv::BRISK::create(c.brisk_threshold);
    case DetectorKind::kAkaze:
      return cv::AKAZE::create(cv::AKAZE::DESCRIPTOR_KAZE, 0, 3,
                               static_cast<float>(c.akaze_threshold));
    case DetectorKind::kOrb:
      return cv::ORB::create(c.max_keypoints, 1.2f, 8, 31, 0, c.orb_wta_k, cv::ORB::HARRIS_SCORE,
                             31, c.orb_fast_threshold);
  }
  return nullptr;
}

int MatchNorm(DetectorKind kind, const DetectorConfig& c) {
  switch (kind) {
    case DetectorKind::kBrisk:
      return cv::NORM_HAMMING;
    case DetectorKind::kOrb:
      return c.orb_wta_k > 2 ? cv::NORM_HAMMING2 : cv::NORM_HAMMING;
    default:
      return cv::NORM_L2;
  }
}

FeatureImage MakeFeatureImage(const cv::Mat& sar, const EnhanceConfig& enhance, int erode_px) {
  FeatureImage out;
  if (sar.empty()) return out;
  cv::Mat clean = sar.clone();
  cv::patchNaNs(clean, 0.0);  // also makes the mask below exclude NaN pixels
  cv::Mat magnitude = MagnitudeImage(clean);
  cv::Mat finite = (magnitude < 1e30) & (magnitude > -1e30);  // excludes +-Inf
  magnitude.setTo(0.0, ~finite);
  if (clean.channels() == 1) clean.setTo(0.0, ~finite);
  out.gray = Enhance8U(clean.channels() == 1 ? clean : magnitude, enhance);
  out.mask = (magnitude > 0.0);
  if (erode_px > 0) {
    const cv::Mat kernel =
        cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * erode_px + 1, 2 * erode_px + 1));
    cv::erode(out.mask, out.mask, kernel, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  }
  return out;
}

namespace {

cv::Size DownsampledSize(int cols, int rows, double factor) {
  if (factor <= 1.0) return {cols, rows};
  return {std::max(1, static_cast<int>(std::lround(cols / factor))),
          std::max(1, static_cast<int>(std::lround(rows / factor)))};
}

}  // namespace

ImageGrid DownsampledGrid(const ImageGrid& grid, double factor) {
  if (factor <= 1.0) return grid;
  const cv::Size size = DownsampledSize(grid.cols, grid.rows, factor);
  return grid.Resized(size.width, size.height);
}

FeatureImage DownsampleFeatureImage(FeatureImage image, double factor, double white_percentile,
                                    ImageGrid* grid) {
  if (factor > 1.0 && !image.gray.empty()) {
    const cv::Size size = DownsampledSize(image.gray.cols, image.gray.rows, factor);
    const int cols = size.width, rows = size.height;
    cv::Mat gray, mask;
    cv::resize(image.gray, gray, cv::Size(cols, rows), 0, 0, cv::INTER_AREA);
    cv::resize(image.mask, mask, cv::Size(cols, rows), 0, 0, cv::INTER_AREA);
    image.gray = gray;
    image.mask = mask >= 255;
    if (grid != nullptr) *grid = grid->Resized(cols, rows);
  }
  NormalizeFeatureContrast(&image, white_percentile);
  return image;
}

void NormalizeFeatureContrast(FeatureImage* image, double white_percentile) {
  if (image->gray.empty()) return;
  if (white_percentile >= 100.0 || cv::countNonZero(image->mask) == 0) {
    cv::normalize(image->gray, image->gray, 0, 255, cv::NORM_MINMAX, CV_8U);
    return;
  }
  // Percentile of the measured pixels from their 8-bit histogram.
  std::array<long long, 256> hist{};
  long long total = 0;
  for (int r = 0; r < image->gray.rows; ++r) {
    const std::uint8_t* g = image->gray.ptr<std::uint8_t>(r);
    const std::uint8_t* m = image->mask.ptr<std::uint8_t>(r);
    for (int c = 0; c < image->gray.cols; ++c) {
      if (m[c]) ++hist[g[c]], ++total;
    }
  }
  int lo = 0;
  while (hist[lo] == 0) ++lo;
  const double target = static_cast<double>(total) * std::max(0.0, white_percentile) / 100.0;
  long long seen = 0;
  int hi = lo;
  for (int v = 0; v < 256; ++v) {
    seen += hist[v];
    hi = v;
    if (static_cast<double>(seen) >= target) break;
  }
  if (hi <= lo) {
    cv::normalize(image->gray, image->gray, 0, 255, cv::NORM_MINMAX, CV_8U);
    return;
  }
  image->gray.convertTo(image->gray, CV_8U, 255.0 / (hi - lo), -255.0 * lo / (hi - lo));
}

FeatureSet ComputeFeatures(const FeatureImage& image, DetectorKind kind,
                           const DetectorConfig& config) {
  FeatureSet out;
  out.detector = kind;
  out.norm_type = MatchNorm(kind, config);
  if (image.gray.empty() || cv::countNonZero(image.mask) == 0) return out;
  const auto start = std::chrono::steady_clock::now();
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  CreateDetector(kind, config)->detectAndCompute(image.gray, image.mask, keypoints, descriptors);
  // Keep the strongest; ties keep detection order so results are reproducible.
  std::vector<int> order(keypoints.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return keypoints[a].response > keypoints[b].response; });
  if (static_cast<int>(order.size()) > config.max_keypoints) order.resize(config.max_keypoints);
  out.keypoints.reserve(order.size());
  if (!descriptors.empty())
    out.descriptors.create(static_cast<int>(order.size()), descriptors.cols, descriptors.type());
  for (std::size_t k = 0; k < order.size(); ++k) {
    out.keypoints.push_back(keypoints[order[k]]);
    descriptors.row(order[k]).copyTo(out.descriptors.row(static_cast<int>(k)));
  }
  out.detect_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace uwbsar
