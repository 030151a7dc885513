// map.pgm of a run or a session: the navigation grid (backend/navigation_grid.h) from the
// keyframes' detected tiles at their optimised poses, the robot's poses while each tile was
// imaged, and each straight keyframe's wall ridges (frontend/wall_profile.h) — the inputs
// the backend's sensor model takes, gathered here where the frontend may be included.
#pragma once

#include <utility>
#include <vector>

#include "backend/navigation_grid.h"
#include "core/types.h"
#include "imaging/occupancy_grid.h"
#include "slam/app_config.h"
#include "slam/session/session_data.h"
#include "slam/slam_snapshot.h"

namespace uwbsar::slam {

/// The ridges of one keyframe, per sensor (slam.navigation.wall_ridges): none when the robot
/// turned by more than ridge_max_heading_change_deg while it was imaged.
std::vector<WallRidge> KeyframeWallRidges(const NavigationKeyframe& k,
                                          const std::vector<SensorGeometry>& sensors,
                                          const NavigationGridConfig& config);

/// The grid of a run: `corrected` is its corrected trajectory (trajectory.tum), map frame.
OccupancyGrid RunNavigationGrid(const SlamSnapshot& slam,
                                const std::vector<std::pair<TimestampNs, Pose2>>& corrected);

/// What the sensor model takes from a run's keyframes that does not depend on where they are
/// placed: each keyframe with a tile and scans (tile shared with the snapshot, the robot's poses
/// in its anchor frame while it was imaged, wall ridges) and its id, in keyframe order.
/// Gathered once, it serves the grid after every solve (results.mcap).
struct RunNavigationInputs {
  std::vector<NavigationKeyframe> keyframes;  ///< T_map_anchor unset; `detected` -> tiles
  std::vector<int> ids;
  std::vector<cv::Mat> tiles;  ///< the tiles read back (slam/session/tile_store.h), held here
};
/// The tiles are read back once and held by the inputs (do not copy them: keyframes point in).
RunNavigationInputs GatherRunNavigationInputs(const SlamSnapshot& slam);
/// The grid of the keyframes of `inputs` that `slam.poses` holds, placed there (`slam` may be
/// an earlier state of the run the inputs were gathered from: SlamSnapshot::AfterSolve).
OccupancyGrid RunNavigationGrid(const SlamSnapshot& slam, const RunNavigationInputs& inputs,
                                const std::vector<std::pair<TimestampNs, Pose2>>& corrected);

/// The grid of a session (every run in the map frame; unplaced keyframes are left out).
OccupancyGrid SessionNavigationGrid(const SessionData& session, const Config& config);

/// The grid of a saved map as its folder `dir` holds it: map.yaml and its image (map.pgm), read
/// as map_server reads them (an image beyond limits.max_map_image_pixels refused from its
/// header), which `map`, `map --resume` and `merge` made from the runs themselves. Made again
/// from `session` (SessionNavigationGrid) only where the folder has no map.yaml: the session
/// keeps odometry thinned (session.odometry_spacing_m), so lines are cast from other poses and
/// a few cells differ. Throws InputError naming a map.yaml or image that cannot be read.
OccupancyGrid SavedNavigationGrid(const std::string& dir, const SessionData& session,
                                  const Config& config);

}  // namespace uwbsar::slam
