// Guided pass around a validated loop. A loop (i, j) predicts where the
// keyframes near j lie relative to the old keyframes near i: the odometry between j and a
// neighbour q is accurate over a few metres, so T_world_q = T_world_i T_ij T_jq. Each
// neighbour q is paired with the old keyframe o whose tile the prediction puts closest,
// matched where the prediction puts each feature (guided matching), and validated by the AKAZE+ORB
// rule with a lower good-match threshold (PlaceRecognitionConfig::guided); the pair counts only
// when its transform agrees with the prediction. A random false loop predicts pairs whose images do
// not agree, so it finds no such neighbours; a true ring closure finds them even where the
// unguided rule missed them, and its guided pairs support it in the backend
// (backend/loop_support.h) instead of leaving it alone.
#pragma once

#include <vector>

#include "frontend/place_recognition/place_recognizer.h"

namespace uwbsar {

/// The prediction of a guided pair: old keyframe o, neighbour q, T_oq from the loop.
struct GuidedPair {
  const KeyframeFeatures* old_keyframe = nullptr;
  const KeyframeFeatures* query = nullptr;
  Pose2 T_oq_predicted;
};

/// Pairs `q` with the keyframe of `olds` whose tile centre the loop (i -> j, T_ij) predicts
/// nearest to q's, within guided.max_centre_distance_m. Estimates (T_world_anchor) only need
/// to be consistent locally: around i for the olds, around j for q. False when none fits.
bool PredictGuidedPair(const KeyframeFeatures& i, const KeyframeFeatures& j, const Pose2& T_ij,
                       const KeyframeFeatures& q, const std::vector<const KeyframeFeatures*>& olds,
                       const GuidedMatchConfig& guided, GuidedPair* pair);

/// Matches a predicted pair and applies the guided rule: ValidateLoop with
/// guided.min_good_matches, then agreement with the prediction. The attempt's
/// candidate_id is the old keyframe, query_id the neighbour; guided is set.
LoopAttempt GuidedAttempt(const GuidedPair& pair, const PlaceRecognitionConfig& pr);

}  // namespace uwbsar
