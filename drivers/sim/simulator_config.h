// Configuration of the environment and robot simulator (`uwbsar simulate`).
// Part of the configuration (slam/app_config.h aggregates it); fields are read and
// written by the generic loader in core/config_io.h.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace uwbsar {

/// A point target of the simulated environment (e.g. a metal pole), in the world (map) frame.
struct PointTargetConfig {
  double x_m = 0.0;     ///< world position
  double y_m = 0.0;     ///< world position
  double rcs_m2 = 0.5;  ///< radar cross-section (a metal pole: about 0.1 .. 1 m^2)

  template <class V>
  void Visit(V& v) {
    v("x_m", x_m);
    v("y_m", y_m);
    v("rcs_m2", rcs_m2);
  }
};

/// Simulated robot motion along a route (differential drive, trapezoidal speed profiles).
struct SimRouteConfig {
  double speed_mps = 0.2;          ///< cruise speed
  double accel_mps2 = 0.3;         ///< linear acceleration and braking
  double turn_rate_radps = 0.8;    ///< top rate of turns on the spot
  double turn_accel_radps2 = 1.5;  ///< angular acceleration of turns on the spot
  double corner_radius_m = 0.3;    ///< corners up to 120 deg are rounded with this radius;
                                   ///< sharper ones (reversals) stop and turn on the spot
  double pause_s = 1.0;            ///< standstill before the start and after the end
  double start_x_m = 0.0;          ///< built-in routes start here (world frame) ...
  double start_y_m = 0.0;          ///< ...
  double start_yaw_deg = 0.0;      ///< ... heading this way
  double depart_distance_m = 7.5;  ///< depart-return: distance driven out before turning back
  double loop_length_m = 7.0;      ///< loop: rectangle this long along the start heading ...
  double loop_width_m = 0.6;       ///< ... and this wide, turning left
  double clearance_m = 0.15;       ///< a route passing closer to an occupied cell is an error

  template <class V>
  void Visit(V& v) {
    v("speed_mps", speed_mps);
    v("accel_mps2", accel_mps2);
    v("turn_rate_radps", turn_rate_radps);
    v("turn_accel_radps2", turn_accel_radps2);
    v("corner_radius_m", corner_radius_m);
    v("pause_s", pause_s);
    v("start_x_m", start_x_m);
    v("start_y_m", start_y_m);
    v("start_yaw_deg", start_yaw_deg);
    v("depart_distance_m", depart_distance_m);
    v("loop_length_m", loop_length_m);
    v("loop_width_m", loop_width_m);
    v("clearance_m", clearance_m);
  }
};

/// Simulated radar echoes from the occupancy grid and point targets.
struct SimRadarConfig {
  double rate_hz = 100.0;                 ///< scan rate of every radar
  double cell_rcs_m2 = 0.01;              ///< mean radar cross-section of one occupied cell;
                                          ///< each cell draws its own (exponential: speckle)
  int scatterers_per_cell = 4;            ///< random scatterers per occupied cell
  double penetration_depth_m = 0.05;      ///< occupied cells lit behind a ray's first hit
  double max_angle_deg = 80.0;            ///< nothing farther off boresight is seen
  double beam_3db_half_angle_deg = 30.0;  ///< two-way -3 dB angle of the Gaussian beam pattern
  double coupling_amplitude = 0.3;        ///< direct antenna coupling pulse at range 0
  double noise_std = 0.02;                ///< white thermal noise per sample (0.02: the
                                          ///< paper's real strip shows this floor up to
                                          ///< its blind band; 0.005 left the band too wide)
  std::vector<PointTargetConfig> point_targets;  ///< e.g. metal poles, in the world frame

  template <class V>
  void Visit(V& v) {
    v("rate_hz", rate_hz);
    v("cell_rcs_m2", cell_rcs_m2);
    v("scatterers_per_cell", scatterers_per_cell);
    v("penetration_depth_m", penetration_depth_m);
    v("max_angle_deg", max_angle_deg);
    v("beam_3db_half_angle_deg", beam_3db_half_angle_deg);
    v("coupling_amplitude", coupling_amplitude);
    v("noise_std", noise_std);
    v("point_targets", point_targets);
  }
};

/// Simulated yaw-rate gyro of the base (drivers/sim/gyro_model.h). Defaults: the Kobuki's
/// published specification (factory calibrated, 1 axis, 110 deg/s; heading in 0.01 deg), and
/// where it is silent the datasheet of its gyro chip, ST L3G4200D (Doc ID 17116): sources and
/// derivations in config/default.yaml, simulator.odometry.gyro.
struct SimGyroConfig {
  double rate_noise_density_dps_per_sqrt_hz = 0.03;  ///< white rate noise (L3G4200D Rn)
  double turn_on_bias_std_dps = 0.03;  ///< bias left after the factory calibration, drawn per
                                       ///< run: the zero-rate drift of 0.03 dps/degC for 1 degC
  /// The turn-on bias fixed at this many turn_on_bias_std_dps (e.g. +3 or -3, to test a run
  /// with a bias of that size and sign); none: drawn from the run's seed.
  std::optional<double> turn_on_bias_sigmas;
  double bias_walk_dps_per_sqrt_s = 0.0005;  ///< random walk of the bias: 0.03 dps (1 degC of
                                             ///< zero-rate drift) in one hour
  double scale_error = 0.0003;  ///< the gyro over-reports rates by this fraction: sensitivity
                                ///< drift of 2 % over 65 degC, for 1 degC
  double range_dps = 110.0;     ///< faster rates saturate at this (Kobuki: 110 deg/s)
  double angle_resolution_deg = 0.01;  ///< the base reports its heading in these steps (0: none)

  template <class V>
  void Visit(V& v) {
    v("rate_noise_density_dps_per_sqrt_hz", rate_noise_density_dps_per_sqrt_hz);
    v("turn_on_bias_std_dps", turn_on_bias_std_dps);
    v("turn_on_bias_sigmas", turn_on_bias_sigmas);
    v("bias_walk_dps_per_sqrt_s", bias_walk_dps_per_sqrt_s);
    v("scale_error", scale_error);
    v("range_dps", range_dps);
    v("angle_resolution_deg", angle_resolution_deg);
  }
};

/// Simulated odometry of the base: wheel encoder ticks with systematic and random errors,
/// integrated like the base does (Kobuki figures by default); with the kobuki_gyro profile the
/// heading comes from the gyro and the wheels give only the distance, as kobuki_node's /odom
/// does by default (use_imu_heading).
struct SimOdometryConfig {
  std::string profile = "kobuki_gyro";  ///< kobuki_gyro: heading from the gyro, distance from
                                        ///< the wheels; wheel: both from the wheels
  std::string topic = "/odom";          ///< nav_msgs/Odometry topic of wheel odometry
  std::string ground_truth_topic = "/ground_truth/odom";  ///< topic of the true poses

  double rate_hz = 50.0;                  ///< wheel odometry rate
  double ground_truth_rate_hz = 200.0;    ///< ground-truth pose rate
  double wheel_radius_m = 0.035;          ///< wheel radius the base assumes
  double wheelbase_m = 0.230;             ///< wheel separation the base assumes
  double ticks_per_revolution = 2578.33;  ///< encoder ticks per wheel turn
  double wheel_scale_error = 0.005;       ///< encoders over-report wheel travel by this
                                          ///< fraction (true wheels smaller than assumed; a
                                          ///< calibrated base). No loop can observe it: it
                                          ///< bounds the ATE from below unless the base's
                                          ///< calibration is given (`uwbsar calibrate`)
  double wheel_scale_asymmetry = 0.0007;  ///< right minus left scale error: heading drift
                                          ///< of about 1.7 deg per 10 m straight
  double wheelbase_error = 0.02;          ///< true wheelbase is this fraction shorter than
                                          ///< assumed: turns are under-reported
  double wheel_slip_std = 0.01;           ///< random error of each wheel's travel per step,
                                          ///< as a fraction of that travel
  SimGyroConfig gyro;                     ///< the gyro of the kobuki_gyro profile

  template <class V>
  void Visit(V& v) {
    v("profile", profile);
    v("topic", topic);
    v("ground_truth_topic", ground_truth_topic);
    v("rate_hz", rate_hz);
    v("ground_truth_rate_hz", ground_truth_rate_hz);
    v("wheel_radius_m", wheel_radius_m);
    v("wheelbase_m", wheelbase_m);
    v("ticks_per_revolution", ticks_per_revolution);
    v("wheel_scale_error", wheel_scale_error);
    v("wheel_scale_asymmetry", wheel_scale_asymmetry);
    v("wheelbase_error", wheelbase_error);
    v("wheel_slip_std", wheel_slip_std);
    v("gyro", gyro);
  }
};

/// Simulated 2-D LiDAR (sensor_msgs/LaserScan), ray cast in the occupancy grid.
struct SimLaserConfig {
  bool enabled = false;         ///< also write simulated laser scans (`simulate --laser`)
  std::string topic = "/scan";  ///< sensor_msgs/LaserScan topic
  double rate_hz = 10.0;        ///< scan rate
  int num_beams = 360;          ///< beams over a full turn
  double min_range_m = 0.15;    ///< closer returns are reported as invalid
  double max_range_m = 12.0;    ///< farther returns are reported as +inf
  double noise_std_m = 0.01;    ///< Gaussian range noise

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled);
    v("topic", topic);
    v("rate_hz", rate_hz);
    v("num_beams", num_beams);
    v("min_range_m", min_range_m);
    v("max_range_m", max_range_m);
    v("noise_std_m", noise_std_m);
  }
};

/// A changed building for a later run of the same map (day 2; drivers/sim/scene_change.h): small
/// objects added beside the route, small objects of the map removed or moved, doors closed or
/// opened. Off while `seed` is null; the map file stays as it is (the day-1 building).
struct SimSceneChangeConfig {
  std::optional<std::uint64_t> seed;  ///< null: the map's building unchanged; a number: the change
  int objects_added = 6;              ///< new objects beside the route
  int objects_removed = 2;            ///< small objects of the map taken away
  int objects_moved = 2;              ///< small objects of the map put elsewhere nearby
  int doors_closed = 1;               ///< doorways of the map closed (never one the route uses)
  int doors_opened = 1;               ///< door-wide openings made in thin walls
  double object_size_min_m = 0.15;    ///< added objects: squares of a side drawn in [min, max]
  double object_size_max_m = 0.25;    ///< ...
  double distance_min_m = 0.7;  ///< added and moved objects: centre this far from the route ...
  double distance_max_m = 1.3;  ///< ... at most this far (added ones)
  double object_max_extent_m = 0.5;   ///< isolated blobs of the map at most this big are objects
  double move_min_m = 0.3;            ///< a moved object goes this far ...
  double move_max_m = 1.0;            ///< ... to this far
  double door_width_min_m = 0.6;      ///< a doorway is a gap this wide in a straight wall ...
  double door_width_max_m = 1.2;      ///< ... at most this wide; opened doors: 0.9 m
  double wall_max_thickness_m = 0.3;  ///< walls thicker than this hold no door
  double reach_m = 3.0;  ///< removed, moved objects and toggled doors lie this close to the route

  template <class V>
  void Visit(V& v) {
    v("seed", seed);
    v("objects_added", objects_added);
    v("objects_removed", objects_removed);
    v("objects_moved", objects_moved);
    v("doors_closed", doors_closed);
    v("doors_opened", doors_opened);
    v("object_size_min_m", object_size_min_m);
    v("object_size_max_m", object_size_max_m);
    v("distance_min_m", distance_min_m);
    v("distance_max_m", distance_max_m);
    v("object_max_extent_m", object_max_extent_m);
    v("move_min_m", move_min_m);
    v("move_max_m", move_max_m);
    v("door_width_min_m", door_width_min_m);
    v("door_width_max_m", door_width_max_m);
    v("wall_max_thickness_m", wall_max_thickness_m);
    v("reach_m", reach_m);
  }
};

/// People walking past during a run (drivers/sim/walking_people.h): moving reflectors the radars
/// and the LiDAR see, each walking to and fro on a straight path beside the route.
struct SimPeopleConfig {
  int count = 0;               ///< people walking during the run (0: none)
  double width_m = 0.4;        ///< a person is a disc this wide
  double speed_mps = 1.0;      ///< walking speed
  double offset_m = 1.0;       ///< their path runs this far beside the route (nearer, down to
                               ///< width_m, where the way is narrower) ...
  double walk_length_m = 6.0;  ///< ... and is this long, walked to and fro (shorter where a
                               ///< wall ends it; at least 1 m)
  double rcs_m2 = 0.5;         ///< radar cross-section of a person

  template <class V>
  void Visit(V& v) {
    v("count", count);
    v("width_m", width_m);
    v("speed_mps", speed_mps);
    v("offset_m", offset_m);
    v("walk_length_m", walk_length_m);
    v("rcs_m2", rcs_m2);
  }
};

/// The robot picked up and carried along its route (the kidnapped robot): over the stretch of
/// route [at_path_m, at_path_m + distance_m) its wheels are off the ground, so the wheel encoders
/// count nothing, while a gyro (profile kobuki_gyro) still measures the turns it is carried
/// through; the radars keep scanning where it truly is. The odometry's path and pose stand still,
/// the truth moves on: after the carry the odometry frame is distance_m off the world's.
struct SimCarryConfig {
  std::optional<double> at_path_m;  ///< null: never carried; else where along the route (true
                                    ///< path, m) the carry starts
  double distance_m = 10.0;         ///< how far along the route it is carried

  template <class V>
  void Visit(V& v) {
    v("at_path_m", at_path_m);
    v("distance_m", distance_m);
  }
};

/// The environment and robot simulator (`uwbsar simulate`).
struct SimulatorConfig {
  SimRouteConfig route;
  SimRadarConfig radar;
  SimOdometryConfig odometry;
  SimLaserConfig laser;
  SimSceneChangeConfig scene_change;
  SimPeopleConfig people;
  SimCarryConfig carried;
  double start_time_s = 1700000000.0;  ///< stamp of the first message (s since the Unix epoch)

  template <class V>
  void Visit(V& v) {
    v("route", route);
    v("radar", radar);
    v("odometry", odometry);
    v("laser", laser);
    v("scene_change", scene_change);
    v("people", people);
    v("carried", carried);
    v("start_time_s", start_time_s);
  }
};

/// Semantic checks of simulator.* (ranges, names, consistency); throws ConfigError naming the
/// dotted key and `source_name`.
void Validate(const SimulatorConfig& config, const std::string& source_name);

}  // namespace uwbsar
