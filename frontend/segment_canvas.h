// The canvas one keyframe segment is imaged into, derived from keyframe.* and the sensors'
// sectors by its owner, the keyframe builder, once: KeyframeBuilder allocates it and the limits
// check (slam/config/system_config_limits.cc) refuses settings that make it too large.
#pragma once

#include <vector>

#include "frontend/keyframe_config.h"
#include "imaging/sensor_geometry.h"

namespace uwbsar {

/// The canvas one segment is imaged into: a square around where the segment starts that
/// covers the robot's travel over one spacing (plus one scan step), every sensor's sector and
/// the margin. Computed here once, for KeyframeBuilder and for the limits check
/// (slam/config/system_config_limits.cc), which refuses settings that make it too large.
struct SegmentCanvas {
  double spacing_term_m = 0.0;  ///< 1.05 x keyframe.tile_spacing_m
  double reach_m = 0.0;         ///< farthest corner of any sensor's sector from the robot
  int reach_sensor = 0;         ///< the sensor with that reach
  double margin_m = 0.0;        ///< keyframe.margin_m

  double half_m() const { return spacing_term_m + reach_m + margin_m; }
  /// Half side in pixels (the canvas is 2 x this + 1 pixels wide and high).
  long long HalfPixels(double pixel_m) const;
  double Pixels(double pixel_m) const;
};
SegmentCanvas SegmentCanvasFor(const KeyframeConfig& keyframe,
                               const std::vector<SensorGeometry>& sensors);

}  // namespace uwbsar
