// Routes for the simulated robot: a polyline of waypoints in the world (map)
// frame, either built in (`depart-return`, `loop`) or read from a waypoints file.
//
// Waypoints file: one waypoint per line, `x_m y_m` (whitespace or comma
// separated), '#' starts a comment, blank lines are skipped. At least two
// distinct waypoints; the robot starts on the first, facing the second.
#pragma once

#include <string>
#include <vector>

#include "core/errors.h"
#include "core/limits_config.h"
#include "core/pose2.h"
#include "drivers/sim/simulator_config.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::sim {

struct Route {
  std::string name;
  std::vector<Point2> waypoints;
};

/// `depart-return`: from the start pose, depart_distance_m straight ahead, turn
/// around on the spot and drive back to the start (the paper's experiment).
/// `loop`: a closed rectangle loop_length_m x loop_width_m, turning left, back to the start.
Route BuiltInRoute(const std::string& name, const SimRouteConfig& config);
/// The built-in route names, for help texts and errors.
std::vector<std::string> BuiltInRouteNames();

/// A built-in route name, or else a waypoints file. Throws InputError naming the
/// file and line on malformed input, or listing the built-in names when `spec` is neither.
/// A waypoints file must be a regular file of at most `max_mb` MiB (limits.max_input_file_mb).
Route ResolveRoute(const std::string& spec, const SimRouteConfig& config,
                   double max_mb = LimitsConfig{}.max_input_file_mb);
Route ReadWaypointsFile(const std::string& path, double max_mb = LimitsConfig{}.max_input_file_mb);

}  // namespace uwbsar::sim
