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

/// The whole configuration; config/default.yaml mirrors it field by field.
struct Config {
  PulseConfig pulse;
  std::vector<RadarConfig> radars = DefaultRadars();
  ImagingConfig imaging;
  GatingConfig gating;
  KeyframeConfig keyframe;
  EnhanceConfig enhance;

  template <class V>
  void Visit(V& v) {
    v("pulse", pulse);
    v("radars", radars);
    v("imaging", imaging);
    v("gating", gating);
    v("keyframe", keyframe);
    v("enhance", enhance);
  }
};

}  // namespace uwbsar
