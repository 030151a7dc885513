// Per-radar matching (place_recognition.per_radar). A keyframe tile is the sum of the
// side-looking radars' images; on a revisit that passes the walls at other distances, the
// near wall of one radar sets the contrast of the whole 8-bit feature image and takes most of
// its strongest keypoints, so the far wall seen by the other radar drops out. Each radar's
// part of the tile (Keyframe::sensor_tiles) therefore gets features of its own, with its own
// contrast and keypoint budget. A candidate pair that fails the combined match is matched
// again over these features, each keypoint only against the radars of the other tile that
// look the same way in the world: the same radar on a revisit in the same direction, the
// other radar on one in the opposite direction (the left radar's wall on the way out is the
// right radar's wall on the way back). All pairs of radars go into one RANSAC per detector,
// so both walls of a corridor constrain the transform; the result goes through the paper's
// AKAZE+ORB rule and the loop validation unchanged, in the tiles' anchor frames (the
// per-radar keypoints are stored in pixels of the whole tile's feature grid).
#pragma once

#include "frontend/keyframe.h"
#include "frontend/place_recognition/place_recognition_config.h"
#include "frontend/place_recognition/place_recognizer.h"

namespace uwbsar {

/// Fills k's per-radar features (radar_by_detector for validation.detectors, look_anchor_rad) from
/// the keyframe's sensor tiles; k.grid must already be the whole tile's feature grid. Leaves them
/// empty when the keyframe has no sensor tiles.
void ExtractRadarFeatures(const Keyframe& keyframe, const PlaceRecognizerConfig& config,
                          KeyframeFeatures* k);

/// True when k has per-radar features of at least two radars (counted on the second detector of
/// pr.validation.detectors).
bool HasRadarFeatures(const KeyframeFeatures& k, const PlaceRecognitionConfig& pr);

/// Matches query j's per-radar features against candidate i's (radar pairs as above, from
/// the current T_world_anchor estimates) and validates the pair with `pr` (at feature
/// resolution). The attempt has candidate_id i, by_radar set, and cross_side set when a radar
/// was paired with another one.
LoopAttempt MatchByRadar(const KeyframeFeatures& i, const KeyframeFeatures& j,
                         const PlaceRecognitionConfig& pr);

}  // namespace uwbsar
