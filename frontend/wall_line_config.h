// Configuration of wall landmarks (place_recognition.wall_profiles.landmarks): a straight wall
// that many keyframes see becomes one line in the pose graph, so that a 10-20 m corridor
// stays straight along its whole length (frontend/wall_line.h measures a keyframe's lines,
// slam/wall_landmarks.h associates them, backend/line_landmark.h holds them in the graph).
// Part of WallProfileConfig (frontend/wall_profile_config.h).
#pragma once

#include <string>

namespace uwbsar {

struct WallLineConfig {
  /// true: straight walls become line landmarks; the pairwise wall edges stay only between
  /// keyframes that share no landmark (the two would measure the same wall twice).
  bool enabled = true;
  /// true: only for a base whose odometry calibration is given (backend.calibration_*_mean
  /// not all 0, `uwbsar calibrate`): with its distance scale unknown, a ring closes only by
  /// bending its corridors a little, which straight walls forbid (uncalibrated ring_offices
  /// tours: 2.7-6.2 cm with landmarks against 2.5-5.6 cm without).
  bool require_calibrated_base = true;
  // Measuring a keyframe's lines (frontend/wall_line.h).
  double min_peak_contrast = 3.0;  ///< a wall's profile peak over the profile's floor (median)
  double min_distance_m = 0.3;     ///< walls closer to the anchor than this are not used
  int max_lines_per_side = 1;      ///< the strongest this many walls left and right of the path
  int strips = 5;                  ///< the tile is cut into this many strips along the path;
                                   ///< the wall's position in each gives its angle
  int min_strips = 3;              ///< strips that must show the wall
  double band_m = 0.1;             ///< a strip's peak is searched this far across the wall
                                   ///< (its floor is taken from twice as far)
  double max_fit_rms_m = 0.02;     ///< strips further than this (rms) from one straight line:
                                   ///< not a straight wall (a corner, a doorway's jamb)
  double offset_std_m = 0.03;      ///< standard deviation of a line's measured offset (at its
                                   ///< reference point) ...
  double angle_std_deg = 10.0;     ///< ... and of its measured angle: weak on purpose, the
                                   ///< offsets of many keyframes give a wall its angle (measured
                                   ///< angles of 1 deg weight bent the tours: docs/measurements.md)
  // Associating lines into landmarks (slam/wall_landmarks.h).
  double gate_offset_m = 0.1;   ///< a line joins a landmark within this offset ...
  double gate_angle_deg = 3.0;  ///< ... and this angle of it, seen from the keyframe
  int max_gap = 3;              ///< a track survives this many keyframes in a row that do not
                                ///< see its wall (a doorway); one more ends it
  int min_observations = 3;     ///< keyframes that must see a landmark before it enters the graph

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled);
    v("require_calibrated_base", require_calibrated_base);
    v("min_peak_contrast", min_peak_contrast);
    v("min_distance_m", min_distance_m);
    v("max_lines_per_side", max_lines_per_side);
    v("strips", strips);
    v("min_strips", min_strips);
    v("band_m", band_m);
    v("max_fit_rms_m", max_fit_rms_m);
    v("offset_std_m", offset_std_m);
    v("angle_std_deg", angle_std_deg);
    v("gate_offset_m", gate_offset_m);
    v("gate_angle_deg", gate_angle_deg);
    v("max_gap", max_gap);
    v("min_observations", min_observations);
  }
};
/// Semantic checks of place_recognition.wall_profiles.landmarks.*; throws ConfigError naming
/// the dotted key.
void Validate(const WallLineConfig& config, const std::string& source_name);

}  // namespace uwbsar
