// Configuration structs. Every field has an in-class default equal to the
// paper's value (or the reference code's where the paper is silent), and a
// Visit() that lists the fields by their YAML key so that one generic loader
// (slam/config_io.h) reads, checks and writes them all.
// config/default.yaml documents every field; a test keeps the two in sync.
#pragma once

#include <string>
#include <vector>

namespace uwbsar {

/// Transmitted pulse and receiver sampling (paper Table I, REFERENCE.md section 1).
struct PulseConfig {
  double center_frequency_hz = 7.29e9;      ///< fc
  double bandwidth_hz = 1.4e9;              ///< -6 dB bandwidth (reference code; paper table: 2 GHz)
  double sampling_frequency_hz = 23.328e9;  ///< fs; one range bin = c / (2 fs)
  double amplitude_v = 0.6;                 ///< pulse amplitude (reference code; paper: 1.0 V)

  template <class V>
  void Visit(V& v) {
    v("center_frequency_hz", center_frequency_hz);
    v("bandwidth_hz", bandwidth_hz);
    v("sampling_frequency_hz", sampling_frequency_hz);
    v("amplitude_v", amplitude_v);
  }
};

/// One radar: where it sits on the robot, where it looks, what it sees.
struct RadarConfig {
  std::string name = "left";                ///< label used in logs and outputs
  std::string topic = "/UWBradar0/readings";  ///< bag / ROS 2 topic of its scans
  double mount_x_m = 0.0;                   ///< antenna position in the robot frame (x forward)
  double mount_y_m = 0.18;                  ///< antenna position in the robot frame (y left)
  double boresight_yaw_deg = 90.0;          ///< boresight direction in the robot frame
  double fov_half_angle_deg = 30.0;         ///< half of the effective beam width
  double min_range_m = 0.4;                 ///< pixels closer than this are not imaged
  double max_range_m = 3.0;                 ///< pixels farther than this are not imaged
  double range_offset_m = 0.0;              ///< range of sample 0 (cable/antenna delay)
  int num_samples = 1000;                   ///< expected samples per scan
  int zero_leading_samples = 1;             ///< samples zeroed before use (reference zeroes 1)

  template <class V>
  void Visit(V& v) {
    v("name", name);
    v("topic", topic);
    v("mount_x_m", mount_x_m);
    v("mount_y_m", mount_y_m);
    v("boresight_yaw_deg", boresight_yaw_deg);
    v("fov_half_angle_deg", fov_half_angle_deg);
    v("min_range_m", min_range_m);
    v("max_range_m", max_range_m);
    v("range_offset_m", range_offset_m);
    v("num_samples", num_samples);
    v("zero_leading_samples", zero_leading_samples);
  }
};

/// The paper's robot: left radar looks to +90 deg, right radar to -90 deg.
inline std::vector<RadarConfig> DefaultRadars() {
  RadarConfig left;
  RadarConfig right;
  right.name = "right";
  right.topic = "/UWBradar1/readings";
  right.mount_y_m = -0.18;
  right.boresight_yaw_deg = -90.0;
  return {left, right};
}

/// Back-projection (paper section "Back-projection Algorithm").
struct ImagingConfig {
  std::string mode = "paper";     ///< "paper": real samples, linear interpolation (as the paper);
                                  ///< "coherent": analytic signal with exp(j 4 pi fc R / c) phase
  double pixel_size_m = 0.005;    ///< 5 mm per pixel, as the paper
  int coherent_oversampling = 4;  ///< analytic-signal upsampling before interpolation (coherent)
  int num_threads = 2;            ///< threads for back-projection (0 = OpenCV default)

  template <class V>
  void Visit(V& v) {
    v("mode", mode);
    v("pixel_size_m", pixel_size_m);
    v("coherent_oversampling", coherent_oversampling);
    v("num_threads", num_threads);
  }
};

/// Scan gating and odometry sanity checks.
struct GatingConfig {
  double min_travel_m = 0.003;     ///< accept a scan after this much robot travel (paper: 3 mm)
  double max_odom_jump_m = 0.5;    ///< a larger step between consecutive odometry samples is rejected
  double max_odom_gap_s = 0.5;     ///< scans farther than this from odometry samples are rejected
  double max_scan_latency_s = 1.0; ///< scans waiting longer than this for odometry are dropped

  template <class V>
  void Visit(V& v) {
    v("min_travel_m", min_travel_m);
    v("max_odom_jump_m", max_odom_jump_m);
    v("max_odom_gap_s", max_odom_gap_s);
    v("max_scan_latency_s", max_scan_latency_s);
  }
};

/// Keyframe tiles: overlapping SAR images of L metres of path (the paper's regions).
struct KeyframeConfig {
  double tile_length_m = 2.0;   ///< path length imaged into one tile (paper: 400 px = 2 m)
  double tile_spacing_m = 1.0;  ///< path length between tile starts (paper: 1 m step)
  double margin_m = 0.25;       ///< extra border around the sensors' reach, in the anchor frame

  template <class V>
  void Visit(V& v) {
    v("tile_length_m", tile_length_m);
    v("tile_spacing_m", tile_spacing_m);
    v("margin_m", margin_m);
  }
};

/// Image enhancement for display and features (paper section "UWB SAR Imaging").
struct EnhanceConfig {
  double blur_sigma_px = 2.0;         ///< Gaussian blur of the positive image
  double display_range_db = 30.0;     ///< dynamic range of log-magnitude display (coherent)
  std::string colormap = "inferno";   ///< PNG colour map: gray, inferno, jet, viridis, magma, hot

  template <class V>
  void Visit(V& v) {
    v("blur_sigma_px", blur_sigma_px);
    v("display_range_db", display_range_db);
    v("colormap", colormap);
  }
};

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
  double loop_width_m = 0.8;       ///< ... and this wide, turning left
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
  double noise_std = 0.005;               ///< white thermal noise per sample
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

/// Simulated wheel odometry: encoder ticks with systematic and random errors, integrated
/// like the base does (Kobuki figures by default).
struct SimOdometryConfig {
  std::string topic = "/odom";  ///< nav_msgs/Odometry topic of wheel odometry
  std::string ground_truth_topic = "/ground_truth/odom";  ///< topic of the true poses

  double rate_hz = 50.0;                  ///< wheel odometry rate
  double ground_truth_rate_hz = 200.0;    ///< ground-truth pose rate
  double wheel_radius_m = 0.035;          ///< wheel radius the base assumes
  double wheelbase_m = 0.230;             ///< wheel separation the base assumes
  double ticks_per_revolution = 2578.33;  ///< encoder ticks per wheel turn
  double wheel_scale_error = 0.015;       ///< encoders over-report wheel travel by this
                                          ///< fraction (true wheels smaller than assumed)
  double wheel_scale_asymmetry = 0.0012;  ///< right minus left scale error: heading drift
                                          ///< of about 3 deg per 10 m straight
  double wheelbase_error = 0.02;          ///< true wheelbase is this fraction shorter than
                                          ///< assumed: turns are under-reported
  double wheel_slip_std = 0.02;           ///< random error of each wheel's travel per step,
                                          ///< as a fraction of that travel

  template <class V>
  void Visit(V& v) {
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

/// The environment and robot simulator (`uwbsar simulate`).
struct SimulatorConfig {
  SimRouteConfig route;
  SimRadarConfig radar;
  SimOdometryConfig odometry;
  SimLaserConfig laser;
  double start_time_s = 1700000000.0;  ///< stamp of the first message (s since the Unix epoch)

  template <class V>
  void Visit(V& v) {
    v("route", route);
    v("radar", radar);
    v("odometry", odometry);
    v("laser", laser);
    v("start_time_s", start_time_s);
  }
};
/// The whole configuration; config/default.yaml mirrors it field by field.
struct Config {
  PulseConfig pulse;
  std::vector<RadarConfig> radars = DefaultRadars();
  ImagingConfig imaging;
  GatingConfig gating;
  KeyframeConfig keyframe;
  EnhanceConfig enhance;
  SimulatorConfig simulator;

  template <class V>
  void Visit(V& v) {
    v("pulse", pulse);
    v("radars", radars);
    v("imaging", imaging);
    v("gating", gating);
    v("keyframe", keyframe);
    v("enhance", enhance);
    v("simulator", simulator);
  }
};

}  // namespace uwbsar
