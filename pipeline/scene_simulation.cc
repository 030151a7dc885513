#include "pipeline/scene_simulation.h"

#include <cmath>

#include "drivers/sim/sim_stream.h"
#include "pipeline/app_config.h"

namespace uwbsar::pipeline {

MapRun MapSimulationInScene(const Config& config, const std::string& map_yaml,
                            const std::string& route, std::uint64_t scene_seed, std::uint64_t seed,
                            const Pose2& T_odom_world) {
  const sim::SimScenario scenario = sim::MakeScenario(config, map_yaml, route, scene_seed);
  sim::SimStream stream(config, scenario, seed);
  sim::SimMessage msg;
  const std::string description = "simulated " + route + " in " + map_yaml + " (scene seed " +
                                  std::to_string(scene_seed) + ", seed " + std::to_string(seed) +
                                  ")";
  return MapStream(config, description, [&](MapRun* r) {
    if (!stream.Next(&msg)) return false;
    if (r->messages++ == 0) r->first_stamp_ns = msg.stamp_ns;
    r->last_stamp_ns = msg.stamp_ns;
    switch (msg.kind) {
      case sim::SimMessage::Kind::kGroundTruth:
        r->ground_truth.push_back(msg.pose);
        break;
      case sim::SimMessage::Kind::kOdometry:
        ++r->odometry_messages;
        msg.pose.T_world_robot = T_odom_world * msg.pose.T_world_robot;
        r->slam->AddOdometry(msg.pose);
        break;
      case sim::SimMessage::Kind::kRadarScan:
        ++r->radar_messages;
        r->slam->AddScan(msg.scan);
        break;
      case sim::SimMessage::Kind::kLaserScan:
        break;
    }
    return true;
  });
}

Pose2 RouteStart(const Config& config) {
  const auto& r = config.simulator.route;
  return {r.start_x_m, r.start_y_m, r.start_yaw_deg * M_PI / 180.0};
}

}  // namespace uwbsar::pipeline
