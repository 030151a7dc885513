// Scoring of a simulated run localised in a saved map (slam/localization/localize_job.h) against
// the simulator's ground truth, as the changed-building acceptance of localisation asks:
//  - first fix: the odometry path from the run's start to the keyframe that placed it;
//  - lost after the fix: keyframes decided "lost" after that one;
//  - error: the run's trajectory in the map frame (each odometry sample corrected by the latest
//    placed keyframe, from the first fix on) against the truth with no alignment, since a
//    simulated map's frame is the world's (its first keyframe is held at its true pose): RMS and
//    the worst sample;
//  - false fix: a keyframe that (re)placed the robot where its corrected pose lies more than
//    false_fix_m from the truth.
#pragma once

#include <string>

#include "slam/localization/localize_job.h"
#include "slam/map_job.h"

namespace uwbsar::eval {

struct LocalizationEvaluation {
  bool placed = false;
  double first_fix_path_m = 0.0;
  int keyframes = 0;
  int after_fix = 0;        ///< keyframes decided after the first fix
  int lost_after_fix = 0;   ///< of those, "lost"
  int registered = 0;       ///< of those, registered against a map tile at least once
  int with_loops = 0;       ///< of those, with a feature loop into the map
  int relocalisations = 0;  ///< keyframes that (re)placed the robot, the first fix included
  int false_fixes = 0;
  double rmse_m = 0.0;  ///< map frame, unaligned, from the first fix on
  double max_m = 0.0;
};

LocalizationEvaluation EvaluateLocalization(const slam::LocalizeRun& run, double false_fix_m = 0.5);
/// One line: first fix, lost, registered, error.
std::string FormatLocalizationEvaluation(const LocalizationEvaluation& e);

/// The odometry's path (LocalizeRun::odometry path_m) when the truth had driven `true_path_m`
/// (its path summed from the ground-truth poses); the last one when it never did.
double OdometryPathAtTruePath(const slam::LocalizeRun& run, double true_path_m);
/// The odometry path from `from_path_m` to the end of the first keyframe ending after it that
/// (re)placed the robot (a kidnapped robot relocalised); -1 when none did.
double PathToRelocalisation(const slam::LocalizeRun& run, double from_path_m);

/// Writes to `out_file` the waypoints of the route in `route_file` from `from_fraction` of its
/// length on (a day-2 run that starts part of the way round a tour). Throws InputError as
/// sim::ReadWaypointsFile does, std::runtime_error when the file cannot be written.
void WriteRouteTail(const std::string& route_file, double from_fraction,
                    const std::string& out_file);

/// The error of a mapped run's trajectory in its map frame against the truth, unaligned (the
/// bound a localisation in that map is held to: its map is no closer to the truth than this).
AteResult MapFrameError(const slam::MapRun& run);

}  // namespace uwbsar::eval
