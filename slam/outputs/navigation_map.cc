#include "slam/outputs/navigation_map.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "frontend/wall_profile.h"
#include "slam/outputs/session_outputs.h"

namespace uwbsar::slam {
namespace {

/// The sensors' reach across the path: the profile spans this either side of the anchor.
double ProfileHalfWidth(const NavigationKeyframe& k, const std::vector<SensorGeometry>& sensors) {
  double reach = 0.0;
  for (const SensorGeometry& s : sensors) {
    reach = std::max(reach, std::hypot(s.T_robot_sensor.x_m, s.T_robot_sensor.y_m) + s.max_range_m);
  }
  double far = 0.0;  // the robot's farthest position from the anchor
  for (const Pose2& p : k.T_anchor_robot) far = std::max(far, std::hypot(p.x_m, p.y_m));
  return reach + far + 0.1;
}

/// The wall ridges of every keyframe (slam.navigation.wall_ridges): they depend on the tile and
/// the robot's poses in its anchor frame only, not on where the keyframe is placed.
void AddWallRidges(std::vector<NavigationKeyframe>* keyframes,
                   const std::vector<SensorGeometry>& sensors, const Config& config) {
  if (!config.slam.navigation.wall_ridges) return;
  for (NavigationKeyframe& k : *keyframes) {
    k.ridges = KeyframeWallRidges(k, sensors, config.slam.navigation);
  }
}

OccupancyGrid Build(const std::vector<NavigationKeyframe>& keyframes,
                    const std::vector<Pose2>& path, const std::vector<SensorGeometry>& sensors,
                    const Config& config) {
  const float reference = TileReferenceLevel(keyframes, config.slam.occupancy_reference_percentile);
  return BuildNavigationGrid(keyframes, path, sensors, config.slam.navigation,
                             config.slam.occupancy_resolution_m, reference,
                             config.limits.max_image_pixels);
}

}  // namespace

std::vector<WallRidge> KeyframeWallRidges(const NavigationKeyframe& k,
                                          const std::vector<SensorGeometry>& sensors,
                                          const NavigationGridConfig& config) {
  std::vector<WallRidge> ridges(sensors.size());
  if (k.T_anchor_robot.size() < 2) return ridges;
  // Straight: every heading within ridge_max_heading_change_deg of the first.
  const double h0 = k.T_anchor_robot.front().yaw_rad;
  double lo = 0.0, hi = 0.0;
  for (const Pose2& p : k.T_anchor_robot) {
    const double d = NormalizeAngle(p.yaw_rad - h0);
    lo = std::min(lo, d), hi = std::max(hi, d);
  }
  if (hi - lo > config.ridge_max_heading_change_deg * M_PI / 180.0) return ridges;
  const double heading = NormalizeAngle(h0 + 0.5 * (lo + hi));
  WallProfileConfig profile_config;
  profile_config.bin_m = k.grid.resolution_m;
  profile_config.half_width_m = ProfileHalfWidth(k, sensors);
  const WallProfile profile = ComputeWallProfile(*k.detected, k.grid, heading, profile_config);
  const float top = *std::max_element(profile.bins.begin(), profile.bins.end());
  if (!(top > 0.0f) || profile.contrast < config.ridge_min_contrast) return ridges;
  // Bins are less the floor: floor = top / (contrast - 1), so a side peak m stands
  // 1 + m / floor times over the floor.
  const double floor = top / (profile.contrast - 1.0);
  const double nx = -std::sin(heading), ny = std::cos(heading);
  const double half = profile.half_width_m();
  const int num_bins = static_cast<int>(profile.bins.size());
  auto bin_of = [&](double offset_m) {
    return std::clamp(static_cast<int>(std::floor((offset_m + half) / profile.bin_m)), 0,
                      num_bins - 1);
  };
  for (std::size_t s = 0; s < sensors.size(); ++s) {
    double antenna = 0.0, along = 0.0;  // mean offset of the antenna; its look along the normal
    for (const Pose2& robot : k.T_anchor_robot) {
      const Pose2 a = robot * sensors[s].T_robot_sensor;
      antenna += nx * a.x_m + ny * a.y_m;
      along += nx * std::cos(a.yaw_rad) + ny * std::sin(a.yaw_rad);
    }
    antenna /= static_cast<double>(k.T_anchor_robot.size());
    along /= static_cast<double>(k.T_anchor_robot.size());
    if (std::abs(along) < 0.5) continue;  // looks along the path, not across it
    const int side = along > 0 ? 1 : -1;
    const int b0 = bin_of(antenna + side * sensors[s].min_range_m);
    const int b1 = bin_of(antenna + side * sensors[s].max_range_m);
    float peak = 0.0f;
    for (int b = b0; b != b1 + side; b += side) peak = std::max(peak, profile.bins[b]);
    if (!(peak > 0.0f) || 1.0 + peak / floor < config.ridge_min_contrast) continue;
    // The wall's near face: the first bin rising to ridge_fraction of the side's peak.
    for (int b = b0; b != b1 + side; b += side) {
      if (profile.bins[b] < config.ridge_fraction * peak) continue;
      ridges[s].found = true;
      ridges[s].normal_x = nx;
      ridges[s].normal_y = ny;
      ridges[s].offset_m = (b + (side > 0 ? 0.0 : 1.0)) * profile.bin_m - half;
      break;
    }
  }
  return ridges;
}

RunNavigationInputs GatherRunNavigationInputs(const SlamSnapshot& slam) {
  const auto& odometry = slam.odometry;
  RunNavigationInputs inputs;
  inputs.tiles.reserve(slam.tiles.size());  // keyframes point into it: never reallocated
  for (const TileSnapshot& t : slam.tiles) {
    if (!t.has_scans || t.detected.empty()) continue;
    NavigationKeyframe k;
    inputs.tiles.push_back(t.detected.Load());
    k.detected = &inputs.tiles.back();
    k.grid = t.detected_grid;
    const Pose2 T_anchor_world = t.T_world_anchor.Inverse();
    auto it = std::lower_bound(
        odometry.begin(), odometry.end(), t.first_scan_ns,
        [](const OdometryEntry& e, TimestampNs stamp) { return e.stamp_ns < stamp; });
    for (; it != odometry.end() && it->stamp_ns <= t.last_scan_ns; ++it) {
      k.T_anchor_robot.push_back(T_anchor_world * it->T_world_robot);
    }
    inputs.keyframes.push_back(std::move(k));
    inputs.ids.push_back(t.id);
  }
  AddWallRidges(&inputs.keyframes, slam.sensors, *slam.config);
  return inputs;
}

OccupancyGrid RunNavigationGrid(const SlamSnapshot& slam, const RunNavigationInputs& inputs,
                                const std::vector<std::pair<TimestampNs, Pose2>>& corrected) {
  std::vector<NavigationKeyframe> placed;
  for (std::size_t i = 0; i < inputs.keyframes.size(); ++i) {
    const auto pose = slam.poses.find(inputs.ids[i]);
    if (pose == slam.poses.end()) continue;  // not in this state (a later keyframe)
    placed.push_back(inputs.keyframes[i]);
    placed.back().T_map_anchor = pose->second;
  }
  std::vector<Pose2> path;
  for (const auto& [stamp, pose] : corrected) path.push_back(pose);
  return Build(placed, path, slam.sensors, *slam.config);
}

OccupancyGrid RunNavigationGrid(const SlamSnapshot& slam,
                                const std::vector<std::pair<TimestampNs, Pose2>>& corrected) {
  return RunNavigationGrid(slam, GatherRunNavigationInputs(slam), corrected);
}

OccupancyGrid SessionNavigationGrid(const SessionData& session, const Config& config) {
  // Odometry is by trajectory, then in time (path_m grows): each run's samples are one span.
  using Iter = std::vector<SessionOdometry>::const_iterator;
  std::map<int, std::pair<Iter, Iter>> runs;
  for (Iter it = session.odometry.begin(); it != session.odometry.end(); ++it) {
    auto [run, added] = runs.insert({it->trajectory, {it, it + 1}});
    if (!added) run->second.second = it + 1;
  }
  std::vector<NavigationKeyframe> keyframes;
  std::vector<cv::Mat> tiles;               // read back once, held while the grid is made
  tiles.reserve(session.keyframes.size());  // keyframes point into it: never reallocated
  for (const SessionKeyframe& s : session.keyframes) {
    if (s.detected.empty()) continue;
    NavigationKeyframe k;
    tiles.push_back(s.detected.Load());
    k.detected = &tiles.back();
    k.grid = s.detected_grid;
    k.T_map_anchor = s.T_map_anchor;
    const Pose2 T_anchor_odom = s.T_odom_anchor.Inverse();
    const auto run = runs.find(s.trajectory);
    if (run != runs.end()) {
      auto it = std::lower_bound(
          run->second.first, run->second.second, s.path_begin_m,
          [](const SessionOdometry& o, double path_m) { return o.path_m < path_m; });
      for (; it != run->second.second && it->path_m <= s.path_end_m; ++it) {
        k.T_anchor_robot.push_back(T_anchor_odom * it->T_odom_robot);
      }
    }
    keyframes.push_back(std::move(k));
  }
  std::vector<Pose2> path;
  for (const SessionTrajectory& t : session.trajectories) {
    for (const auto& [stamp, pose] : CorrectedTrajectory(session, t.id)) path.push_back(pose);
  }
  std::vector<SensorGeometry> sensors;
  for (const RadarConfig& radar : config.radars) {
    sensors.push_back(SensorGeometry::FromConfig(radar, config.pulse));
  }
  AddWallRidges(&keyframes, sensors, config);
  return Build(keyframes, path, sensors, config);
}

OccupancyGrid SavedNavigationGrid(const std::string& dir, const SessionData& session,
                                  const Config& config) {
  const std::filesystem::path yaml = std::filesystem::path(dir) / "map.yaml";
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(yaml, ec))) {
    return SessionNavigationGrid(session, config);
  }
  return LoadOccupancyGrid(yaml.string(), config.limits.max_map_image_pixels);
}

}  // namespace uwbsar::slam
