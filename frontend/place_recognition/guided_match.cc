#include "frontend/place_recognition/guided_match.h"

#include <cmath>
#include <limits>

namespace uwbsar {

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
  attempt.akaze = MatchFeatures(o.akaze, q.akaze, pr.matching);
  attempt.orb = MatchFeatures(o.orb, q.orb, pr.matching);
  LoopValidationConfig rule = pr.validation;
  rule.min_good_matches = pr.guided.min_good_matches;
  attempt.validation = ValidateLoop(o.id, o.grid, q.id, q.grid, attempt.akaze, attempt.orb, rule);
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
