#include "slam/scene_simulation.h"

#include <cmath>

#include "drivers/sim/sim_source.h"
#include "slam/app_config.h"

namespace uwbsar::slam {

MapRun MapSimulationInScene(const Config& config, const std::string& map_yaml,
                            const std::string& route, std::uint64_t scene_seed, std::uint64_t seed,
                            const Pose2& T_odom_world) {
  const sim::SimScenario scenario = sim::MakeScenario(config, map_yaml, route, scene_seed);
  sim::SimSource source(config, scenario, seed, T_odom_world);
  const std::string description = "simulated " + route + " in " + map_yaml + " (scene seed " +
                                  std::to_string(scene_seed) + ", seed " + std::to_string(seed) +
                                  ")";
  return MapSource(config, description, source);
}

Pose2 RouteStart(const Config& config) {
  const auto& r = config.simulator.route;
  return {r.start_x_m, r.start_y_m, r.start_yaw_deg * M_PI / 180.0};
}

}  // namespace uwbsar::slam
