#include "drivers/sim/simulator_config.h"

#include <cmath>
#include <string>
#include <utility>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const SimulatorConfig& s, const std::string& src) {
  const std::string k = "simulator.";
  const SimRouteConfig& r = s.route;
  Require(r.speed_mps > 0 && r.speed_mps <= 5, src, k + "route.speed_mps", "must be in (0, 5]");
  Require(r.accel_mps2 > 0, src, k + "route.accel_mps2", "must be > 0");
  Require(r.turn_rate_radps > 0, src, k + "route.turn_rate_radps", "must be > 0");
  Require(r.turn_accel_radps2 > 0, src, k + "route.turn_accel_radps2", "must be > 0");
  Require(r.corner_radius_m >= 0, src, k + "route.corner_radius_m", "must be >= 0");
  Require(r.pause_s >= 0, src, k + "route.pause_s", "must be >= 0");
  Require(r.depart_distance_m > 0, src, k + "route.depart_distance_m", "must be > 0");
  Require(r.loop_length_m > 0, src, k + "route.loop_length_m", "must be > 0");
  Require(r.loop_width_m > 0, src, k + "route.loop_width_m", "must be > 0");
  Require(r.clearance_m >= 0, src, k + "route.clearance_m", "must be >= 0");
  const SimRadarConfig& a = s.radar;
  Require(a.rate_hz > 0 && a.rate_hz <= 10000, src, k + "radar.rate_hz", "must be in (0, 10000]");
  Require(a.cell_rcs_m2 >= 0, src, k + "radar.cell_rcs_m2", "must be >= 0");
  Require(a.scatterers_per_cell >= 1 && a.scatterers_per_cell <= 64, src,
          k + "radar.scatterers_per_cell", "must be in [1, 64]");
  Require(a.penetration_depth_m >= 0, src, k + "radar.penetration_depth_m", "must be >= 0");
  Require(a.max_angle_deg > 0 && a.max_angle_deg <= 180, src, k + "radar.max_angle_deg",
          "must be in (0, 180]");
  Require(a.beam_3db_half_angle_deg > 0, src, k + "radar.beam_3db_half_angle_deg", "must be > 0");
  Require(a.noise_std >= 0, src, k + "radar.noise_std", "must be >= 0");
  for (std::size_t i = 0; i < a.point_targets.size(); ++i) {
    Require(a.point_targets[i].rcs_m2 >= 0, src,
            k + "radar.point_targets[" + std::to_string(i) + "].rcs_m2", "must be >= 0");
  }
  const SimOdometryConfig& o = s.odometry;
  Require(!o.topic.empty(), src, k + "odometry.topic", "must not be empty");
  Require(!o.ground_truth_topic.empty() && o.ground_truth_topic != o.topic, src,
          k + "odometry.ground_truth_topic", "must be set and differ from odometry.topic");
  Require(o.rate_hz > 0 && o.rate_hz <= 10000, src, k + "odometry.rate_hz",
          "must be in (0, 10000]");
  Require(o.ground_truth_rate_hz > 0 && o.ground_truth_rate_hz <= 10000, src,
          k + "odometry.ground_truth_rate_hz", "must be in (0, 10000]");
  Require(o.wheel_radius_m > 0, src, k + "odometry.wheel_radius_m", "must be > 0");
  Require(o.wheelbase_m > 0, src, k + "odometry.wheelbase_m", "must be > 0");
  Require(o.ticks_per_revolution > 0, src, k + "odometry.ticks_per_revolution", "must be > 0");
  Require(std::abs(o.wheel_scale_error) < 0.5, src, k + "odometry.wheel_scale_error",
          "must be in (-0.5, 0.5)");
  Require(std::abs(o.wheel_scale_asymmetry) < 0.5, src, k + "odometry.wheel_scale_asymmetry",
          "must be in (-0.5, 0.5)");
  Require(std::abs(o.wheelbase_error) < 0.5, src, k + "odometry.wheelbase_error",
          "must be in (-0.5, 0.5)");
  Require(o.wheel_slip_std >= 0 && o.wheel_slip_std < 1, src, k + "odometry.wheel_slip_std",
          "must be in [0, 1)");
  Require(o.profile == "kobuki_gyro" || o.profile == "wheel", src, k + "odometry.profile",
          "must be kobuki_gyro or wheel");
  const SimGyroConfig& g = o.gyro;
  const std::string kg = k + "odometry.gyro.";
  Require(g.rate_noise_density_dps_per_sqrt_hz >= 0 && g.rate_noise_density_dps_per_sqrt_hz < 10,
          src, kg + "rate_noise_density_dps_per_sqrt_hz", "must be in [0, 10)");
  Require(g.turn_on_bias_std_dps >= 0 && g.turn_on_bias_std_dps < 100, src,
          kg + "turn_on_bias_std_dps", "must be in [0, 100)");
  Require(!g.turn_on_bias_sigmas || std::abs(*g.turn_on_bias_sigmas) <= 10, src,
          kg + "turn_on_bias_sigmas", "must be null (drawn from the seed) or in [-10, 10]");
  Require(g.bias_walk_dps_per_sqrt_s >= 0 && g.bias_walk_dps_per_sqrt_s < 10, src,
          kg + "bias_walk_dps_per_sqrt_s", "must be in [0, 10)");
  Require(std::abs(g.scale_error) < 0.5, src, kg + "scale_error", "must be in (-0.5, 0.5)");
  Require(g.range_dps > 0 && g.range_dps <= 10000, src, kg + "range_dps", "must be in (0, 10000]");
  Require(g.angle_resolution_deg >= 0 && g.angle_resolution_deg <= 10, src,
          kg + "angle_resolution_deg", "must be in [0, 10]");
  const SimLaserConfig& l = s.laser;
  Require(!l.topic.empty(), src, k + "laser.topic", "must not be empty");
  Require(l.rate_hz > 0 && l.rate_hz <= 1000, src, k + "laser.rate_hz", "must be in (0, 1000]");
  Require(l.num_beams >= 1 && l.num_beams <= 100000, src, k + "laser.num_beams",
          "must be in [1, 100000]");
  Require(l.min_range_m >= 0, src, k + "laser.min_range_m", "must be >= 0");
  Require(l.max_range_m > l.min_range_m, src, k + "laser.max_range_m", "must exceed min_range_m");
  Require(l.noise_std_m >= 0, src, k + "laser.noise_std_m", "must be >= 0");
  const SimSceneChangeConfig& c = s.scene_change;
  const std::string kc = k + "scene_change.";
  for (const auto& [key, count] : {std::pair<const char*, int>{"objects_added", c.objects_added},
                                   {"objects_removed", c.objects_removed},
                                   {"objects_moved", c.objects_moved},
                                   {"doors_closed", c.doors_closed},
                                   {"doors_opened", c.doors_opened}}) {
    Require(count >= 0 && count <= 1000, src, kc + key, "must be in [0, 1000]");
  }
  Require(c.object_size_min_m > 0, src, kc + "object_size_min_m", "must be > 0");
  Require(c.object_size_max_m >= c.object_size_min_m && c.object_size_max_m <= 5, src,
          kc + "object_size_max_m", "must be in [object_size_min_m, 5]");
  Require(c.distance_min_m > 0, src, kc + "distance_min_m", "must be > 0");
  Require(c.distance_max_m >= c.distance_min_m, src, kc + "distance_max_m",
          "must be >= distance_min_m");
  Require(c.object_max_extent_m > 0 && c.object_max_extent_m <= 5, src, kc + "object_max_extent_m",
          "must be in (0, 5]");
  Require(c.move_min_m >= 0, src, kc + "move_min_m", "must be >= 0");
  Require(c.move_max_m >= c.move_min_m && c.move_max_m <= 20, src, kc + "move_max_m",
          "must be in [move_min_m, 20]");
  Require(c.door_width_min_m > 0, src, kc + "door_width_min_m", "must be > 0");
  Require(c.door_width_max_m >= c.door_width_min_m && c.door_width_max_m <= 5, src,
          kc + "door_width_max_m", "must be in [door_width_min_m, 5]");
  Require(c.wall_max_thickness_m > 0 && c.wall_max_thickness_m <= 2, src,
          kc + "wall_max_thickness_m", "must be in (0, 2]");
  Require(c.reach_m > 0 && c.reach_m <= 50, src, kc + "reach_m", "must be in (0, 50]");
  const SimPeopleConfig& p = s.people;
  const std::string kp = k + "people.";
  Require(p.count >= 0 && p.count <= 1000, src, kp + "count", "must be in [0, 1000]");
  Require(p.width_m > 0 && p.width_m <= 5, src, kp + "width_m", "must be in (0, 5]");
  Require(p.speed_mps > 0 && p.speed_mps <= 10, src, kp + "speed_mps", "must be in (0, 10]");
  Require(p.offset_m >= 0 && p.offset_m <= 20, src, kp + "offset_m", "must be in [0, 20]");
  Require(p.walk_length_m > 0 && p.walk_length_m <= 100, src, kp + "walk_length_m",
          "must be in (0, 100]");
  Require(p.rcs_m2 >= 0, src, kp + "rcs_m2", "must be >= 0");
  const SimCarryConfig& carried = s.carried;
  Require(!carried.at_path_m || (*carried.at_path_m >= 0 && *carried.at_path_m <= 1e6), src,
          k + "carried.at_path_m", "must be null or in [0, 1e6]");
  Require(carried.distance_m > 0 && carried.distance_m <= 1e4, src, k + "carried.distance_m",
          "must be in (0, 10000]");
  // The simulated bag's headers hold ROS 2 times (core/stamp_range.h).
  Require(s.start_time_s >= 0 && s.start_time_s < 2147483647.0, src, k + "start_time_s",
          "must be in [0, 2147483647) (seconds since 1970, until 2038-01-19: a ROS 2 time)");
}

}  // namespace uwbsar
