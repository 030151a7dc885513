// Loop-closure detection for a stream of keyframes: each new keyframe's features of the
// detectors the validation rule names (validation.detectors, the paper's AKAZE and ORB) are
// computed once and cached; candidates come from the spatial index (candidate_search.h); each
// candidate pair is matched with both detectors, validated by the paper's rule
// (loop_validator.h) and, when accepted, becomes a
// metric LoopConstraint. Every attempt is reported with its reason.
#pragma once

#include <limits>
#include <memory>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/radar_config.h"
#include "frontend/keyframe.h"
#include "frontend/place_recognition/candidate_search.h"
#include "frontend/place_recognition/feature_matcher.h"
#include "frontend/place_recognition/features.h"
#include "frontend/place_recognition/loop_validator.h"
#include "frontend/place_recognition/place_recognition_config.h"
#include "imaging/enhance_config.h"

namespace uwbsar {

/// What is kept of a keyframe for place recognition (the tile image is not needed).
struct KeyframeFeatures {
  int id = 0;
  ImageGrid grid;
  DetectorMap<FeatureSet> by_detector;  ///< the validation pair's detectors
  Point2 centre_anchor;  ///< mean robot position of the tile's scans, in the anchor frame
  double path_begin_m = 0.0;
  double stamp_s = std::numeric_limits<double>::quiet_NaN();  ///< its time (NaN: unknown)
  Pose2 T_world_anchor;  ///< latest estimate (odometry, or optimised via UpdatePose)
  /// Per-radar features (radar_match.h; empty without sensor tiles): every radar's keypoints
  /// in pixels of `grid`, class_id = sensor id.
  DetectorMap<FeatureSet> radar_by_detector;
  std::vector<double> look_anchor_rad;  ///< per sensor id: boresight at mid-tile, anchor frame
  /// The feature image, packed (PackForRefinement), kept for the dense refinement of near
  /// agreements (validation.refinement.enabled); null otherwise, and in a saved session's.
  /// Shared: copies of the features (a session's capture) do not copy it.
  std::shared_ptr<const std::vector<unsigned char>> refinement_image;

  /// The features of `kind` (an empty set when they were not computed, e.g. a saved session
  /// made with other detectors: nothing matches it).
  const FeatureSet& Features(DetectorKind kind) const;
  const FeatureSet& RadarFeatures(DetectorKind kind) const;
};

/// Tile pixels per feature pixel (detectors.feature_resolution_m / `tile_pixel_m`, >= 1): the
/// one value derived from the tile pixel size (imaging.pixel_size_m) that place recognition
/// uses. Computed once per configuration (PlaceRecognizerConfig) and handed down.
double FeatureDownsampling(const DetectorConfig& detectors, double tile_pixel_m);
/// The same from any configuration holding place_recognition.detectors and imaging.pixel_size_m.
template <class Config>
double FeatureDownsampling(const Config& config) {
  return FeatureDownsampling(config.place_recognition.detectors, config.imaging.pixel_size_m);
}

/// What place recognition reads: its own section, the enhancement of the feature image, the
/// feature downsampling derived from the tile pixel size, and where each radar looks (the
/// per-radar pass pairs radars by their look direction). Nothing else of the configuration
/// reaches it.
struct PlaceRecognizerConfig {
  PlaceRecognitionConfig place_recognition;
  EnhanceConfig enhance;
  double feature_downsampling = 1.0;  ///< tile pixels per feature pixel (FeatureDownsampling)
  std::vector<double> radar_boresight_yaw_deg;  ///< radars[*].boresight_yaw_deg, by sensor id
  double tile_pixel_m = 0.005;  ///< imaging.pixel_size_m: the tile pixel the paper's pixel
                                ///< thresholds are given at (image files are matched at it too)

  PlaceRecognizerConfig() = default;
  /// Its sections of any configuration holding them, with feature_downsampling derived from
  /// imaging.pixel_size_m (implicit: callers hand the configuration they hold).
  template <class Config>
  PlaceRecognizerConfig(const Config& config)  // NOLINT(google-explicit-constructor)
      : place_recognition(config.place_recognition),
        enhance(config.enhance),
        feature_downsampling(FeatureDownsampling(config)),
        tile_pixel_m(config.imaging.pixel_size_m) {
    for (const RadarConfig& r : config.radars)
      radar_boresight_yaw_deg.push_back(r.boresight_yaw_deg);
  }
};

/// `pr` with its pixel thresholds (RANSAC, the detector pair's agreement, inlier spread, residual
/// floor), which are the paper's at the tile resolution, divided by `factor` (feature pixel
/// size / tile pixel size) so that they keep their size in metres.
PlaceRecognitionConfig AtFeatureResolution(PlaceRecognitionConfig pr, double factor);

/// Computes a keyframe's cached features (the detectors of validation.detectors) from its tile, at
/// detectors.feature_resolution_m (`grid` is then the downsampled tile's grid).
KeyframeFeatures ExtractKeyframeFeatures(const Keyframe& keyframe,
                                         const PlaceRecognizerConfig& config);

/// The loop rule's pair (validation.detectors) matched between two keyframes' whole-tile
/// features: `older` is the train side, as every loop attempt, localisation and merge uses it.
DetectorMap<MatchResult> MatchDetectorPair(const KeyframeFeatures& older,
                                           const KeyframeFeatures& newer,
                                           const PlaceRecognitionConfig& pr);

struct LoopAttempt {
  int candidate_id = 0;  ///< i (the older keyframe); the new one is j
  int query_id = -1;     ///< j when not the new keyframe (a guided pair before it), else -1
  bool guided = false;   ///< from the guided pass around a validated loop (guided_match.h)

  /// Matched radar by radar (radar_match.h) after the combined tiles failed; cross_side
  /// when a radar was paired with another one.
  bool by_radar = false;
  bool cross_side = false;
  DetectorMap<MatchResult> matches;  ///< per detector of the validation pair
  LoopValidation validation;

  /// The match of `kind` (an empty result when that detector was not run).
  const MatchResult& Match(DetectorKind kind) const;
};

struct PlaceRecognitionResult {
  int keyframe_id = 0;
  CandidateSet candidates;
  std::vector<LoopAttempt> attempts;
  std::vector<LoopConstraint> loops;  ///< accepted: T_ij = pose of keyframe j in i (j is the
                                      ///< new keyframe, or an earlier one for guided pairs)
  double features_ms = 0.0;
  double matching_ms = 0.0;  ///< all candidates, matching and validation
};

class PlaceRecognizer {
 public:
  explicit PlaceRecognizer(const PlaceRecognizerConfig& config);

  /// Processes a new keyframe: features, candidates, matching, validation; then adds it
  /// to the database. `T_world_anchor_estimate` is the best current estimate of its
  /// anchor (odometry chained onto the last optimised pose); by default its odometry pose.
  PlaceRecognitionResult Process(const Keyframe& keyframe);
  PlaceRecognitionResult Process(const Keyframe& keyframe, const Pose2& T_world_anchor_estimate);
  /// Same, for features computed elsewhere (e.g. in a worker thread).
  PlaceRecognitionResult Process(KeyframeFeatures features, double features_ms);

  /// Moves a stored keyframe after the pose graph corrected it.
  void UpdatePose(int id, const Pose2& T_world_anchor);
  /// Forgets a keyframe the map retired: it is no longer a candidate (unknown ids are ignored).
  void Remove(int id);
  const KeyframeFeatures* Find(int id) const;
  std::size_t size() const { return database_.size(); }

 private:
  Point2 CentreInWorld(const KeyframeFeatures& k) const;
  /// The guided pass (guided_match.h): around the best loop validated for `features`,
  /// its earlier neighbours; else the new keyframe itself when a loop (guided ones included)
  /// was validated at most guided.neighbours keyframes before it.
  void GuidedPass(const KeyframeFeatures& features, PlaceRecognitionResult* result);

  PlaceRecognizerConfig config_;  ///< place_recognition at the feature resolution
  KeyframeIndex index_;
  std::unordered_map<int, std::unique_ptr<KeyframeFeatures>> database_;
  double path_at_last_loop_m_ = 0.0;
  double time_at_last_loop_s_ = std::numeric_limits<double>::quiet_NaN();
  double path_at_last_global_m_ = -1e300;  ///< path of the last query without a pose prior
  bool have_path_origin_ = false;
  LoopConstraint last_loop_;  ///< the last loop validated (unguided, or guided forward)
  bool have_last_loop_ = false;
  std::set<std::pair<int, int>> validated_pairs_;  ///< (i, j) of every validated loop
};

}  // namespace uwbsar
