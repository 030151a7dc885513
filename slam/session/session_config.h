// Configuration of saved sessions: joining a new run to a saved map
// (`uwbsar map --resume`, `uwbsar merge`) and localising in one (`uwbsar localize`).
// Part of the configuration (slam/app_config.h aggregates it).
#pragma once

#include <string>

#include "core/named_enum.h"

namespace uwbsar {

/// session.joined_mosaic: how the map of several runs is combined (see SessionConfig).
enum class JoinedMosaic { kNormalizedMax, kNormalizedMean, kMean };
template <>
struct EnumNames<JoinedMosaic> {
  static constexpr std::pair<JoinedMosaic, const char*> kNames[] = {
      {JoinedMosaic::kNormalizedMax, "normalized_max"},
      {JoinedMosaic::kNormalizedMean, "normalized_mean"},
      {JoinedMosaic::kMean, "mean"}};
};

struct SessionConfig {
  int connect_min_loops = 1;           ///< validated loops into the saved map that agree on where
                                       ///< the new run lies before it is connected (the issue: one
                                       ///< accepted loop; 2: a lone false loop cannot place a
                                       ///< run, but placement comes later)
  double connect_agree_m = 0.3;        ///< two such loops agree when the run's placements they
  double connect_agree_deg = 5.0;      ///< imply differ by less than this
  double search_radius_m = 2.0;        ///< once placed: saved keyframes this close to a new
                                       ///< keyframe's estimate are its candidates
  double localize_lost_after_m = 3.0;  ///< localize: no fix for this much path = "lost"
  int localize_window_keyframes = 10;  ///< localize: keyframes in the sliding window
  /// The map of several runs (map --resume, merge), each run's tiles in units of its own
  /// slam.occupancy_reference_percentile level (a brighter run neither out-shines nor raises
  /// the threshold over another's walls): "normalized_mean" = all tiles averaged, a vote of
  /// the runs where both observed (best by the cell-wise difference against a grid);
  /// "normalized_max" = the per-pixel max, saturated at 1: the occupied cells are the union
  /// of the runs' (best recall and F1, more false walls); "mean" = every tile averaged
  /// unscaled, as within one run.
  JoinedMosaic joined_mosaic = JoinedMosaic::kNormalizedMean;
  /// Joining a run (map --resume, merge): true = the saved map's keyframes keep their poses and
  /// the new run is fitted to them (as Cartographer loads a saved state frozen): a joined run
  /// cannot bend a finished map, and what was placed in its frame stays put; false = both are
  /// optimised together.
  bool freeze_saved_map = true;
  /// session.uwbsar holds each keyframe's tile as float32 (true: lossless, about 630 KiB per
  /// keyframe) or in 1023 linear levels of the tile's maximum (false: about 90 KiB; the
  /// error is at most half a level, 0.26 % of the demo's reference level, and the observed
  /// pixels are kept: slam/session/blob_codec.h EncodeTile).
  bool lossless_tiles = false;
  /// session.uwbsar keeps a run's odometry sample once the robot moved this far (or turned
  /// 1 deg, or 1 s passed) since the last one kept, the first and last always: the trajectory
  /// of a long run costs the session a few kB per 10 m instead of 2 kB per second driven
  /// (0: every sample).
  double odometry_spacing_m = 0.02;

  template <class V>
  void Visit(V& v) {
    v("connect_min_loops", connect_min_loops);
    v("connect_agree_m", connect_agree_m);
    v("connect_agree_deg", connect_agree_deg);
    v("search_radius_m", search_radius_m);
    v("localize_lost_after_m", localize_lost_after_m);
    v("localize_window_keyframes", localize_window_keyframes);
    v("joined_mosaic", joined_mosaic);
    v("freeze_saved_map", freeze_saved_map);
    v("lossless_tiles", lossless_tiles);
    v("odometry_spacing_m", odometry_spacing_m);
  }
};

/// Semantic checks of session.* (ranges, names, consistency); throws ConfigError naming the
/// dotted key and `source_name`.
void Validate(const SessionConfig& config, const std::string& source_name);

}  // namespace uwbsar
