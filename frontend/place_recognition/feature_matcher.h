// The paper's matching pipeline between two cached feature sets: brute-force kNN
// (k = 2) with the descriptor's norm, Lowe's ratio test, then a RANSAC similarity
// (estimateAffinePartial2D: rotation, uniform scale, translation). The RANSAC
// inliers are the paper's "good matches".
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/place_recognition/features.h"
#include "frontend/place_recognition/place_recognition_config.h"

namespace uwbsar {

/// Matching of tile b (query) against tile a (train). The transform maps pixels of b
/// to pixels of a: p_a = scale * R(rotation) * p_b + (tx, ty), in pixel coordinates
/// (x = column, y = row, rotation measured from +x towards +row).
struct MatchResult {
  DetectorKind detector = DetectorKind::kAkaze;
  int keypoints_a = 0;
  int keypoints_b = 0;
  int ratio_matches = 0;  ///< kNN matches that passed the ratio test
  int good_matches = 0;   ///< RANSAC inliers
  bool has_transform = false;
  double scale = 0.0;
  double tx_px = 0.0;
  double ty_px = 0.0;
  double rotation_deg = 0.0;
  cv::Matx23d affine = cv::Matx23d::zeros();  ///< [s R | t], p_a = affine * (p_b, 1)
  double residual_rms_px = 0.0;        ///< RMS distance of the inliers from the fitted transform
  double match_ms = 0.0;               ///< kNN + ratio test + RANSAC (features were cached)
  std::vector<cv::DMatch> matches;     ///< ratio-test matches: queryIdx in b, trainIdx in a
  std::vector<unsigned char> inlier;   ///< per entry of `matches`
  std::vector<cv::Point2d> inliers_a;  ///< inlier keypoint positions in a (pixels)
  std::vector<cv::Point2d> inliers_b;  ///< ... and in b
  std::string reason;                  ///< why there is no transform (empty when has_transform)

  /// Good matches as a percentage of ratio-test matches (the paper's "% good matches").
  double good_match_percent() const {
    return ratio_matches > 0 ? 100.0 * good_matches / ratio_matches : 0.0;
  }
};

MatchResult MatchFeatures(const FeatureSet& a, const FeatureSet& b,
                          const FeatureMatchConfig& config);

/// Guided matching: the same, but keypoint k of b may only match the keypoints of a that
/// `allowed` (CV_8U, b rows x a columns, non-zero = allowed) permits, e.g. those near its
/// predicted position; a keypoint with a single allowed neighbour keeps it without the
/// ratio test (the prediction already singled it out).
MatchResult MatchFeatures(const FeatureSet& a, const FeatureSet& b,
                          const FeatureMatchConfig& config, const cv::Mat& allowed);

}  // namespace uwbsar
