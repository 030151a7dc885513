// Configuration of per-radar matching (place_recognition.per_radar): each keyframe keeps
// one AKAZE and one ORB feature set per radar, detected on that radar's part of the tile
// alone; a candidate pair that fails the combined match is matched again radar by radar,
// pairing the radars that look the same way in the world (same side on a revisit in the
// same direction, across sides on a revisit in the opposite direction). Part of the
// configuration (frontend/place_recognition/place_recognition_config.h includes it).
#pragma once

namespace uwbsar {

struct RadarMatchConfig {
  bool enabled = true;                     ///< false: the combined tile only (as the paper)
  int max_keypoints = 100;                 ///< strongest kept per radar and detector (each
                                           ///< keyframe stores this many more per radar)
  double max_look_difference_deg = 100.0;  ///< radar a of one tile is matched with radar b of
                                           ///< the other when their boresights, in the world,
                                           ///< differ by at most this (they see the same walls)

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled);
    v("max_keypoints", max_keypoints);
    v("max_look_difference_deg", max_look_difference_deg);
  }
};

}  // namespace uwbsar
