#include "frontend/place_recognition/guided_match.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

namespace uwbsar {
namespace {

/// Which keypoints of o each keypoint of q may match (b rows x a columns, for MatchFeatures):
/// those within radius_m of where the predicted transform puts it, and only when the match
/// is distinct: its descriptor distance below `ratio` times that of the best keypoint of o
/// outside the window. Without that check a wrong prediction is half confirmed: the window
/// holds no true partner, its nearest lookalikes match (a lone keypoint in a window even
/// passes MatchFeatures' ratio test unopposed) and RANSAC fits a transform pulled towards
/// the prediction (GuidedPrecisionAcceptanceTest: 8 deg off predicted, 5 deg off accepted).
cv::Mat NearPrediction(const FeatureSet& o, const ImageGrid& grid_o, const FeatureSet& q,
                       const ImageGrid& grid_q, const Pose2& T_oq, double radius_m, double ratio) {
  cv::Mat allowed = cv::Mat::zeros(q.size(), o.size(), CV_8U);
  if (q.size() == 0 || o.size() == 0 || q.descriptors.type() != o.descriptors.type() ||
      q.descriptors.cols != o.descriptors.cols) {
    return allowed;  // MatchFeatures reports the mismatch
  }
  const bool hamming = o.norm_type == cv::NORM_HAMMING || o.norm_type == cv::NORM_HAMMING2;
  cv::Mat distance;
  cv::batchDistance(q.descriptors, o.descriptors, distance, hamming ? CV_32S : CV_32F,
                    cv::noArray(), o.norm_type);
  distance.convertTo(distance, CV_32F);
  const double radius_px = radius_m / grid_o.resolution_m;
  std::vector<unsigned char> inside(static_cast<std::size_t>(o.size()));
  for (int k = 0; k < q.size(); ++k) {
    const cv::Point2f& pq = q.keypoints[static_cast<std::size_t>(k)].pt;
    const Point2 p = T_oq * grid_q.PixelToMetric(pq.x, pq.y);
    const double col = grid_o.XToCol(p.x_m), row = grid_o.YToRow(p.y_m);
    float best_outside = std::numeric_limits<float>::infinity();
    for (int m = 0; m < o.size(); ++m) {
      const cv::Point2f& po = o.keypoints[static_cast<std::size_t>(m)].pt;
      inside[static_cast<std::size_t>(m)] = std::hypot(po.x - col, po.y - row) <= radius_px;
      if (!inside[static_cast<std::size_t>(m)]) {
        best_outside = std::min(best_outside, distance.at<float>(k, m));
      }
    }
    for (int m = 0; m < o.size(); ++m) {
      if (inside[static_cast<std::size_t>(m)] && distance.at<float>(k, m) < ratio * best_outside) {
        allowed.at<unsigned char>(k, m) = 1;
      }
    }
  }
  return allowed;
}

}  // namespace

bool PredictGuidedPair(const KeyframeFeatures& i, const KeyframeFeatures& j, const Pose2& T_ij,
                       const KeyframeFeatures& q, const std::vector<const KeyframeFeatures*>& olds,
                       const GuidedMatchConfig& guided, GuidedPair* pair) {
  const Pose2 T_world_q = i.T_world_anchor * T_ij * Between(j.T_world_anchor, q.T_world_anchor);
  const Point2 centre_q = T_world_q * q.centre_anchor;
  double best_m = std::numeric_limits<double>::infinity();
  for (const KeyframeFeatures* o : olds) {
    if (o->id == q.id) continue;
    const Point2 centre_o = o->T_world_anchor * o->centre_anchor;
    const double d = std::hypot(centre_o.x_m - centre_q.x_m, centre_o.y_m - centre_q.y_m);
    if (d <= guided.max_centre_distance_m && d < best_m) {
      best_m = d;
      pair->old_keyframe = o;
      pair->query = &q;
      pair->T_oq_predicted = Between(o->T_world_anchor, T_world_q);
    }
  }
  return std::isfinite(best_m);
}

LoopAttempt GuidedAttempt(const GuidedPair& pair, const PlaceRecognitionConfig& pr) {
  const KeyframeFeatures& o = *pair.old_keyframe;
  const KeyframeFeatures& q = *pair.query;
  LoopAttempt attempt;
  attempt.candidate_id = o.id;
  attempt.query_id = q.id;
  attempt.guided = true;
  for (DetectorKind kind : pr.validation.detectors) {
    const FeatureSet& fo = o.Features(kind);
    const FeatureSet& fq = q.Features(kind);
    attempt.matches[kind] =
        MatchFeatures(fo, fq, pr.matching,
                      NearPrediction(fo, o.grid, fq, q.grid, pair.T_oq_predicted,
                                     pr.guided.max_offset_m, pr.matching.ratio));
  }
  LoopValidationConfig rule = pr.validation;
  rule.min_good_matches = pr.guided.min_good_matches;
  attempt.validation = ValidateLoop(o.id, o.grid, q.id, q.grid, attempt.matches, rule);
  if (!attempt.validation.accepted) return attempt;
  const Pose2& T = attempt.validation.constraint.T_ij;
  const Pose2& P = pair.T_oq_predicted;
  const double offset_m = std::hypot(T.x_m - P.x_m, T.y_m - P.y_m);
  const double yaw_deg = std::abs(NormalizeAngle(T.yaw_rad - P.yaw_rad)) * 180.0 / M_PI;
  if (offset_m > pr.guided.max_offset_m || yaw_deg > pr.guided.max_yaw_deg) {
    attempt.validation.accepted = false;
    attempt.validation.reason = "guided: disagrees with the loop's prediction";
  }
  return attempt;
}

}  // namespace uwbsar
