// Keypoints and descriptors of one tile for the five detectors of the paper
// (SIFT, SURF, BRISK, AKAZE with the KAZE descriptor, ORB with WTA_K = 4), with the
// paper's settings (Table II) and the strongest max_keypoints kept. Features are
// computed once per keyframe and cached (KeyframeFeatures), never per candidate pair.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <string>
#include <vector>

#include "frontend/place_recognition/detector_kind.h"
#include "frontend/place_recognition/place_recognition_config.h"
#include "imaging/enhance_config.h"
#include "imaging/image_grid.h"

namespace uwbsar {

/// The detector with the configured (paper) settings.
cv::Ptr<cv::Feature2D> CreateDetector(DetectorKind kind, const DetectorConfig& config);
/// Descriptor norm to match with: L2 (SIFT, SURF, AKAZE-KAZE), Hamming (BRISK),
/// Hamming2 (ORB with WTA_K 3 or 4).
int MatchNorm(DetectorKind kind, const DetectorConfig& config);

/// What the detectors see: the paper's 8-bit enhanced image and the mask of imaged
/// pixels, eroded so that the edges of the radar sectors are not taken for features.
struct FeatureImage {
  cv::Mat gray;  ///< CV_8UC1
  cv::Mat mask;  ///< CV_8UC1, 255 where features may be detected
};
/// From a tile (CV_32FC1 paper mode, CV_32FC2 coherent). Non-finite pixels count as
/// not imaged.
FeatureImage MakeFeatureImage(const cv::Mat& sar, const EnhanceConfig& enhance, int erode_px);

/// Averages a feature image down by `factor` (> 1; otherwise unchanged); keeps only pixels
/// whose whole footprint was inside the mask. `grid`, when given, is resized to match
/// (ImageGrid::Resized). Then stretches the contrast (NormalizeFeatureContrast).
FeatureImage DownsampleFeatureImage(FeatureImage image, double factor, double white_percentile,
                                    ImageGrid* grid = nullptr);
/// The grid DownsampleFeatureImage gives an image on `grid` (known before the image is made).
ImageGrid DownsampledGrid(const ImageGrid& grid, double factor);
/// Maps the darkest measured (mask) pixel to 0 and the `white_percentile` percentile of the
/// measured pixels to 255, saturating brighter ones (100 = min-max normalisation). A few
/// very bright scatterers would otherwise leave the rest of the scene in a handful of gray
/// levels, below the detectors' contrast thresholds.
void NormalizeFeatureContrast(FeatureImage* image, double white_percentile);

struct FeatureSet {
  DetectorKind detector = DetectorKind::kAkaze;
  std::vector<cv::KeyPoint> keypoints;  ///< strongest first
  cv::Mat descriptors;                  ///< one row per keypoint
  int norm_type = cv::NORM_L2;
  double detect_ms = 0.0;

  int size() const { return static_cast<int>(keypoints.size()); }
};

/// Detects and describes; keeps the max_keypoints strongest (by response).
FeatureSet ComputeFeatures(const FeatureImage& image, DetectorKind kind,
                           const DetectorConfig& config);

}  // namespace uwbsar
