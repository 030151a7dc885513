// Simulated revisits of one building (issue 18): the scene (the scatterers drawn for the
// map's occupied cells) comes from `scene_seed`, the run's noise and odometry errors from
// `seed`, so runs with one scene seed and different seeds see the same building, as a
// robot coming back does (`uwbsar simulate --scene-seed`).
#pragma once

#include <cstdint>
#include <string>

#include "tools/map_job.h"

namespace uwbsar::tools {

/// As MapSimulation, with the scene from `scene_seed`.
MapRun MapSimulationInScene(const Config& config, const std::string& map_yaml,
                            const std::string& route, std::uint64_t scene_seed, std::uint64_t seed);

}  // namespace uwbsar::tools
