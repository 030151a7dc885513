// Simulated revisits of one building: the scene (the scatterers drawn for the
// map's occupied cells) comes from `scene_seed`, the run's noise and odometry errors from
// `seed`, so runs with one scene seed and different seeds see the same building, as a
// robot coming back does (`uwbsar simulate --scene-seed`).
#pragma once

#include <cstdint>
#include <string>

#include "slam/app_config.h"
#include "slam/map_job.h"

namespace uwbsar::slam {

/// As MapSimulation, with the scene from `scene_seed`. The wheel odometry is reported in a
/// frame of its own: T_odom_world * (the simulator's odometry, which starts at the true
/// start pose), e.g. RouteStart^-1 for odometry that starts at zero, as a robot's does; the
/// ground truth stays in the world (map file) frame.
MapRun MapSimulationInScene(const Config& config, const std::string& map_yaml,
                            const std::string& route, std::uint64_t scene_seed, std::uint64_t seed,
                            const Pose2& T_odom_world = {});

/// The pose a built-in route starts at (simulator.route.start_*), in the world frame.
Pose2 RouteStart(const Config& config);

}  // namespace uwbsar::slam
