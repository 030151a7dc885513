#include "frontend/place_recognition/place_recognizer.h"

#include <algorithm>
#include <chrono>
#include <future>
#include <opencv2/imgproc.hpp>

#include "core/types.h"
#include "frontend/place_recognition/dense_refinement.h"
#include "frontend/place_recognition/guided_match.h"
#include "frontend/place_recognition/radar_match.h"

namespace uwbsar {
namespace {

double MsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

const FeatureSet kNoFeatures;

}  // namespace

const FeatureSet& KeyframeFeatures::Features(DetectorKind kind) const {
  return Of(by_detector, kind, kNoFeatures);
}

const FeatureSet& KeyframeFeatures::RadarFeatures(DetectorKind kind) const {
  return Of(radar_by_detector, kind, kNoFeatures);
}

const MatchResult& LoopAttempt::Match(DetectorKind kind) const {
  static const MatchResult kNotMatched;
  return Of(matches, kind, kNotMatched);
}

DetectorMap<MatchResult> MatchDetectorPair(const KeyframeFeatures& older,
                                           const KeyframeFeatures& newer,
                                           const PlaceRecognitionConfig& pr) {
  DetectorMap<MatchResult> matches;
  for (DetectorKind kind : pr.validation.detectors) {
    matches[kind] = MatchFeatures(older.Features(kind), newer.Features(kind), pr.matching);
  }
  return matches;
}

KeyframeFeatures ExtractKeyframeFeatures(const Keyframe& keyframe,
                                         const PlaceRecognizerConfig& config) {
  const DetectorConfig& d = config.place_recognition.detectors;
  KeyframeFeatures k;
  k.id = keyframe.id;
  k.grid = keyframe.grid;
  k.path_begin_m = keyframe.path_begin_m;
  k.stamp_s = NsToSeconds(keyframe.stamp_ns);
  k.T_world_anchor = keyframe.T_world_anchor;
  if (!keyframe.image.empty()) k.grid = DownsampledGrid(keyframe.grid, config.feature_downsampling);
  // The radars' tiles on a thread of their own while the combined tile is done here: they are
  // independent, and each alone leaves a core idle (a feature image is made on one thread, AKAZE
  // keeps about 1.4 busy). The two write different members of k; the radars only read k.grid.
  std::future<void> radars;
  if (config.place_recognition.per_radar.enabled) {
    radars = std::async(std::launch::async, [&] { ExtractRadarFeatures(keyframe, config, &k); });
  }
  const FeatureImage image =  // on k.grid, set above
      DownsampleFeatureImage(MakeFeatureImage(keyframe.image, config.enhance, d.mask_erode_px),
                             config.feature_downsampling, d.white_percentile);
  for (DetectorKind kind : config.place_recognition.validation.detectors)
    k.by_detector[kind] = ComputeFeatures(image, kind, d);
  if (config.place_recognition.validation.refinement.enabled) {
    k.refinement_image =
        std::make_shared<const std::vector<unsigned char>>(PackForRefinement(image));
  }
  if (radars.valid()) radars.get();  // rethrows what the radars' thread threw
  // Where the robot drove while imaging the tile: a better "position" of the tile than
  // the anchor, which sits at its first scan.
  double sx = 0.0, sy = 0.0;
  for (const ImagedScan& s : keyframe.scans) {
    const Pose2 T_anchor_robot = Between(keyframe.T_world_anchor, s.T_world_robot);
    sx += T_anchor_robot.x_m;
    sy += T_anchor_robot.y_m;
  }
  if (!keyframe.scans.empty()) {
    const double n = static_cast<double>(keyframe.scans.size());
    k.centre_anchor = {sx / n, sy / n};
  } else {
    k.centre_anchor =
        keyframe.grid.PixelToMetric(0.5 * (keyframe.grid.cols - 1), 0.5 * (keyframe.grid.rows - 1));
  }
  return k;
}

double FeatureDownsampling(const DetectorConfig& detectors, double tile_pixel_m) {
  const double r = detectors.feature_resolution_m;
  return r > tile_pixel_m ? r / tile_pixel_m : 1.0;
}

PlaceRecognitionConfig AtFeatureResolution(PlaceRecognitionConfig pr, double factor) {
  // The pixel thresholds are the paper's at the tile resolution: at a coarser feature
  // resolution they shrink in pixels so that they keep their size in metres.
  pr.matching.ransac_reprojection_px /= factor;
  pr.validation.max_tx_difference_px /= factor;
  pr.validation.max_ty_difference_px /= factor;
  pr.validation.min_inlier_spread_px /= factor;
  pr.validation.min_residual_px /= factor;
  return pr;
}

PlaceRecognizer::PlaceRecognizer(const PlaceRecognizerConfig& config)
    : config_(config), index_(config.place_recognition.candidates.grid_cell_m) {
  config_.place_recognition =
      AtFeatureResolution(config.place_recognition, config.feature_downsampling);
}

Point2 PlaceRecognizer::CentreInWorld(const KeyframeFeatures& k) const {
  return k.T_world_anchor * k.centre_anchor;
}

PlaceRecognitionResult PlaceRecognizer::Process(const Keyframe& keyframe) {
  return Process(keyframe, keyframe.T_world_anchor);
}

PlaceRecognitionResult PlaceRecognizer::Process(const Keyframe& keyframe,
                                                const Pose2& T_world_anchor_estimate) {
  const auto start = std::chrono::steady_clock::now();
  KeyframeFeatures features = ExtractKeyframeFeatures(keyframe, config_);
  features.T_world_anchor = T_world_anchor_estimate;
  return Process(std::move(features), MsSince(start));
}

PlaceRecognitionResult PlaceRecognizer::Process(KeyframeFeatures features, double features_ms) {
  const PlaceRecognitionConfig& pr = config_.place_recognition;
  PlaceRecognitionResult result;
  result.keyframe_id = features.id;
  result.features_ms = features_ms;
  if (!have_path_origin_) {
    path_at_last_loop_m_ = features.path_begin_m;
    time_at_last_loop_s_ = features.stamp_s;
    have_path_origin_ = true;
  }
  const auto start = std::chrono::steady_clock::now();
  CandidateQuery query;
  query.position_world = CentreInWorld(features);
  query.path_begin_m = features.path_begin_m;
  query.travelled_since_loop_m = features.path_begin_m - path_at_last_loop_m_;
  query.seconds_since_loop_s = features.stamp_s - time_at_last_loop_s_;  // NaN: unknown
  // Re-localisation: after a long stretch without a loop the odometry may have drifted
  // farther than any search radius, so now and then a keyframe is matched against every
  // past keyframe. Once a loop is found the solve corrects the estimates and the prior
  // works again; matching everything on every keyframe would grow with the map.
  CandidateSearchConfig search = pr.candidates;
  if (search.use_pose_prior && search.global_search_every_m > 0 &&
      query.travelled_since_loop_m >= search.global_search_after_m &&
      features.path_begin_m - path_at_last_global_m_ >= search.global_search_every_m) {
    search.use_pose_prior = false;
    path_at_last_global_m_ = features.path_begin_m;
  }
  result.candidates = FindCandidates(index_, query, search);
  FeatureImage new_image;  // unpacked at the first pair that needs it
  for (int id : result.candidates.ids) {
    const KeyframeFeatures& old = *database_.at(id);
    LoopAttempt attempt;
    attempt.candidate_id = id;
    attempt.matches = MatchDetectorPair(old, features, pr);
    // The images are unpacked only for a pair the refinement will look at.
    FeatureImage old_image;
    LoopImages images;
    if (features.refinement_image && old.refinement_image &&
        MayRefine(attempt.matches, pr.validation)) {
      if (new_image.gray.empty()) new_image = UnpackForRefinement(*features.refinement_image);
      old_image = UnpackForRefinement(*old.refinement_image);
      images = {&old_image, &new_image};
    }
    attempt.validation = ValidateLoop(old.id, old.grid, features.id, features.grid, attempt.matches,
                                      pr.validation, images);
    if (!attempt.validation.accepted && pr.per_radar.enabled && HasRadarFeatures(old, pr) &&
        HasRadarFeatures(features, pr)) {
      LoopAttempt by_radar = MatchByRadar(old, features, pr);
      if (by_radar.validation.accepted) attempt = std::move(by_radar);
    }
    if (attempt.validation.accepted) result.loops.push_back(attempt.validation.constraint);
    result.attempts.push_back(std::move(attempt));
  }
  if (!result.loops.empty()) {
    path_at_last_loop_m_ = features.path_begin_m;
    time_at_last_loop_s_ = features.stamp_s;
  }
  GuidedPass(features, &result);
  result.matching_ms = MsSince(start);
  const int id = features.id;
  auto stored = std::make_unique<KeyframeFeatures>(std::move(features));
  index_.Upsert(id, CentreInWorld(*stored), stored->path_begin_m);
  database_[id] = std::move(stored);
  return result;
}

void PlaceRecognizer::GuidedPass(const KeyframeFeatures& features, PlaceRecognitionResult* result) {
  const PlaceRecognitionConfig& pr = config_.place_recognition;
  const int k = pr.guided.neighbours;
  if (k <= 0) return;
  std::vector<const KeyframeFeatures*> queries;  // neighbours of the loop's new keyframe
  const bool recent_loop = have_last_loop_ && features.id - last_loop_.j <= k;
  for (const LoopConstraint& l : result->loops) validated_pairs_.insert({l.i, l.j});
  if (!result->loops.empty()) {
    const LoopConstraint* best = &result->loops.front();
    for (const LoopConstraint& l : result->loops) {
      if (MinGoodMatches(l) > MinGoodMatches(*best)) best = &l;
    }
    last_loop_ = *best;
    have_last_loop_ = true;
    // Only a loop that begins a revisit looks back: later ones have loops before them.
    for (int q = features.id - 1; !recent_loop && q >= features.id - k; --q) {
      if (const KeyframeFeatures* f = Find(q)) queries.push_back(f);
    }
  } else if (recent_loop) {
    queries.push_back(&features);
  }
  if (queries.empty()) return;
  const KeyframeFeatures* i = Find(last_loop_.i);
  const KeyframeFeatures* j = last_loop_.j == features.id ? &features : Find(last_loop_.j);
  if (i == nullptr || j == nullptr) return;
  for (const KeyframeFeatures* q : queries) {
    // Old keyframes around i, far enough back along the path from q not to share its scans.
    std::vector<const KeyframeFeatures*> olds;
    for (int id = i->id - 3 * k; id <= i->id + 3 * k; ++id) {
      const KeyframeFeatures* o = Find(id);
      if (o != nullptr && o->path_begin_m < q->path_begin_m - pr.candidates.exclude_recent_path_m)
        olds.push_back(o);
    }
    GuidedPair pair;
    if (!PredictGuidedPair(*i, *j, last_loop_.T_ij, *q, olds, pr.guided, &pair)) continue;
    if (validated_pairs_.count({pair.old_keyframe->id, q->id})) continue;
    LoopAttempt attempt = GuidedAttempt(pair, pr);
    if (attempt.validation.accepted) {
      result->loops.push_back(attempt.validation.constraint);
      validated_pairs_.insert({pair.old_keyframe->id, q->id});
      // Forward, a guided loop predicts the next keyframes in turn: the pass follows the
      // revisit for as long as each keyframe finds its pair.
      if (q == &features) last_loop_ = attempt.validation.constraint;
    }
    result->attempts.push_back(std::move(attempt));
  }
}

void PlaceRecognizer::UpdatePose(int id, const Pose2& T_world_anchor) {
  auto it = database_.find(id);
  if (it == database_.end()) return;
  it->second->T_world_anchor = T_world_anchor;
  index_.Upsert(id, CentreInWorld(*it->second), it->second->path_begin_m);
}

void PlaceRecognizer::Remove(int id) {
  database_.erase(id);
  index_.Remove(id);
}

const KeyframeFeatures* PlaceRecognizer::Find(int id) const {
  auto it = database_.find(id);
  return it == database_.end() ? nullptr : it->second.get();
}

}  // namespace uwbsar
