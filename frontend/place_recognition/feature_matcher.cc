#include "frontend/place_recognition/feature_matcher.h"

#include <chrono>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>

namespace uwbsar {

MatchResult MatchFeatures(const FeatureSet& a, const FeatureSet& b,
                          const FeatureMatchConfig& config) {
  return MatchFeatures(a, b, config, cv::Mat());
}

MatchResult MatchFeatures(const FeatureSet& a, const FeatureSet& b,
                          const FeatureMatchConfig& config, const cv::Mat& allowed) {
  MatchResult r;
  r.detector = a.detector;
  r.keypoints_a = a.size();
  r.keypoints_b = b.size();
  const auto start = std::chrono::steady_clock::now();
  auto finish = [&](const std::string& reason) {
    r.reason = reason;
    r.match_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return r;
  };
  if (a.detector != b.detector || a.norm_type != b.norm_type) {
    return finish("feature sets of different detectors");
  }
  if (a.size() < 2 || b.size() < 2) return finish("fewer than 2 keypoints in a tile");
  if (a.descriptors.type() != b.descriptors.type() || a.descriptors.cols != b.descriptors.cols) {
    return finish("descriptor layouts differ");
  }
  cv::BFMatcher matcher(a.norm_type, false);
  std::vector<std::vector<cv::DMatch>> knn;
  matcher.knnMatch(b.descriptors, a.descriptors, knn, 2, allowed);
  for (const auto& pair : knn) {
    if ((pair.size() == 1 && !allowed.empty()) ||
        (pair.size() == 2 && pair[0].distance < config.ratio * pair[1].distance)) {
      r.matches.push_back(pair[0]);
    }
  }
  r.ratio_matches = static_cast<int>(r.matches.size());
  if (r.ratio_matches < 2) return finish("fewer than 2 matches passed the ratio test");
  std::vector<cv::Point2f> pa, pb;
  for (const cv::DMatch& m : r.matches) {
    pa.push_back(a.keypoints[m.trainIdx].pt);
    pb.push_back(b.keypoints[m.queryIdx].pt);
  }
  cv::Mat inlier;
  const cv::Mat affine = cv::estimateAffinePartial2D(
      pb, pa, inlier, cv::RANSAC, config.ransac_reprojection_px,
      static_cast<std::size_t>(config.ransac_max_iterations), config.ransac_confidence);
  if (affine.empty() || !cv::checkRange(affine)) return finish("RANSAC found no transform");
  affine.convertTo(r.affine, CV_64F);
  r.inlier.assign(r.matches.size(), 0);
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < r.matches.size(); ++k) {
    if (!inlier.at<unsigned char>(static_cast<int>(k))) continue;
    r.inlier[k] = 1;
    const cv::Point2d q(pb[k].x, pb[k].y);
    const cv::Point2d p(pa[k].x, pa[k].y);
    const cv::Point2d mapped(r.affine(0, 0) * q.x + r.affine(0, 1) * q.y + r.affine(0, 2),
                             r.affine(1, 0) * q.x + r.affine(1, 1) * q.y + r.affine(1, 2));
    sum_sq += (mapped.x - p.x) * (mapped.x - p.x) + (mapped.y - p.y) * (mapped.y - p.y);
    r.inliers_a.push_back(p);
    r.inliers_b.push_back(q);
  }
  r.good_matches = static_cast<int>(r.inliers_a.size());
  if (r.good_matches < 2) return finish("RANSAC kept fewer than 2 inliers");
  r.residual_rms_px = std::sqrt(sum_sq / r.good_matches);
  r.scale = std::hypot(r.affine(0, 0), r.affine(1, 0));
  r.rotation_deg = std::atan2(r.affine(1, 0), r.affine(0, 0)) * 180.0 / M_PI;
  r.tx_px = r.affine(0, 2);
  r.ty_px = r.affine(1, 2);
  if (!(r.scale > 0.0) || !std::isfinite(r.scale)) return finish("degenerate RANSAC transform");
  r.has_transform = true;
  return finish("");
}

}  // namespace uwbsar
