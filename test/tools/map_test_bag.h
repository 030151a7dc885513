// The small `uwbsar map` input of the CLI tests: a synthetic straight run past a wall
// and poles written as a ROS 2 bag, optionally damaged.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "drivers/rosbag/bag_writer.h"
#include "drivers/rosbag/ros_codecs.h"
#include "drivers/sim/synthetic_run.h"
#include "slam/app_config.h"

namespace uwbsar {
namespace map_test {

namespace fs = std::filesystem;

/// A fresh folder named after `name` and this process (ctest runs tests as parallel processes).
inline std::string TempDir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("uwbsar_map_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

/// A bag of a synthetic straight run past a wall and poles; `edit` may drop or
/// change messages before they are written (return false to drop).
struct BagEdits {
  bool radar = true;
  bool odometry = true;
  double odometry_time_shift_s = 0.0;
  double length_m = 4.0;
  /// One more odometry message, stamped 1 ns (the run itself is stamped in 2023).
  bool stray_odometry_at_1ns = false;
  /// The odometry topic name (a non-default one needs slam.odometry_topic).
  std::string odometry_topic = "/odom";
  /// Every radar sample replaced by this value (0: powered but silent radars), if set.
  std::optional<float> radar_sample_value = std::nullopt;
  /// The odometry restarts from zero at this time into the run (a base reset), if set.
  std::optional<double> odometry_reset_at_s = std::nullopt;
  /// The stamp of the run's first message (a recording made in another year), if set.
  std::optional<TimestampNs> start_stamp_ns = std::nullopt;
};

/// Writes the bag as `dir`/run; `truth_tum`, if given, receives the run's true poses (TUM).
inline std::string WriteRunBag(const std::string& dir, const BagEdits& edits,
                               const std::string& truth_tum = "") {
  Config config;
  SyntheticPath path;
  path.length_m = edits.length_m;
  path.speed_mps = 0.5;
  path.radar_rate_hz = 100;
  if (edits.start_stamp_ns) path.start_stamp_ns = *edits.start_stamp_ns;
  std::vector<Scatterer> scene = WallScatterers({-1, 1.6}, {6, 1.6}, 0.01, 0.05);
  for (int i = 0; i < 8; ++i) scene.push_back({{0.5 * i, i % 2 ? -1.2 : 1.0}, 1.0});
  const SyntheticRun run = SimulateRun(config, path, scene, EchoModel{}, 3);
  if (!truth_tum.empty()) {
    std::ofstream tum(truth_tum);
    tum.precision(17);
    for (const OdometrySample& o : run.odometry) {  // exact: the truth
      tum << NsToSeconds(o.stamp_ns) << " " << o.T_world_robot.x_m << " " << o.T_world_robot.y_m
          << " 0 0 0 " << std::sin(0.5 * o.T_world_robot.yaw_rad) << " "
          << std::cos(0.5 * o.T_world_robot.yaw_rad) << "\n";
    }
  }
  const std::string bag = dir + "/run";
  rosbag::BagWriter writer(bag);
  const int left = writer.AddTopic(config.radars[0].topic, rosbag::kFloat32MultiArrayType);
  const int right = writer.AddTopic(config.radars[1].topic, rosbag::kFloat32MultiArrayType);
  const int odom = writer.AddTopic(edits.odometry_topic, rosbag::kOdometryType);
  std::size_t i = 0, j = 0;
  std::optional<Pose2> reset_pose;
  const TimestampNs shift = SecondsToNs(edits.odometry_time_shift_s);
  if (edits.stray_odometry_at_1ns) {
    rosbag::Odometry msg;
    msg.orientation = rosbag::QuaternionFromYaw(0.0);
    writer.WriteMessage(odom, 1, msg);
  }
  while (i < run.odometry.size() || j < run.scans.size()) {
    const bool take_odom =
        j >= run.scans.size() ||
        (i < run.odometry.size() && run.odometry[i].stamp_ns + shift <= run.scans[j].stamp_ns);
    if (take_odom) {
      OdometrySample o = run.odometry[i++];
      if (!edits.odometry) continue;
      if (edits.odometry_reset_at_s &&
          o.stamp_ns >= run.odometry.front().stamp_ns + SecondsToNs(*edits.odometry_reset_at_s)) {
        if (!reset_pose) reset_pose = o.T_world_robot;
        o.T_world_robot = Between(*reset_pose, o.T_world_robot);
      }
      rosbag::Odometry msg;
      msg.header.frame_id = "odom";
      msg.child_frame_id = "base_link";
      msg.position = {o.T_world_robot.x_m, o.T_world_robot.y_m, 0.0};
      msg.orientation = rosbag::QuaternionFromYaw(o.T_world_robot.yaw_rad);
      writer.WriteMessage(odom, o.stamp_ns + shift, msg);
    } else {
      const RadarScan& s = run.scans[j++];
      if (!edits.radar) continue;
      rosbag::Float32MultiArray msg;
      msg.data = s.samples;
      if (edits.radar_sample_value) {
        std::fill(msg.data.begin(), msg.data.end(), *edits.radar_sample_value);
      }
      writer.WriteMessage(s.sensor_id == 0 ? left : right, s.stamp_ns, msg);
    }
  }
  writer.Close();
  return bag;
}

}  // namespace map_test
}  // namespace uwbsar
