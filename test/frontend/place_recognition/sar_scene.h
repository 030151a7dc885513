// Test and benchmark helper: a cluttered point-scatterer scene (two rough walls and
// random objects), simulated radar runs over it with drifting wheel odometry, imaged
// into keyframe tiles by the real frontend, with the true anchor poses kept for
// scoring. Header-only so the benchmark can use it too.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "drivers/sim/synthetic_run.h"
#include "frontend/imaging_frontend.h"
#include "frontend/keyframe.h"
#include "slam/app_config.h"

namespace uwbsar::testing {

/// Walls at y = wall_left_y and y = wall_right_y along x in [x0, x1] with random
/// roughness and reflectivity, plus `objects` clusters (chairs, poles) between them.
inline std::vector<Scatterer> ClutterScene(std::uint64_t seed, double x0 = -3.0, double x1 = 13.0,
                                           double wall_left_y = 1.6, double wall_right_y = -1.4,
                                           int objects = 60) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Scatterer> out;
  for (double y : {wall_left_y, wall_right_y}) {
    for (double x = x0; x < x1; x += 0.02) {
      out.push_back({{x, y + 0.03 * (u(rng) - 0.5)}, 0.2 + 0.8 * u(rng)});
    }
  }
  for (int k = 0; k < objects; ++k) {
    const double cx = x0 + (x1 - x0) * u(rng);
    const double side = u(rng) < 0.5 ? 1.0 : -1.0;
    const double cy = side * (0.6 + 2.2 * u(rng));
    const int parts = 1 + static_cast<int>(4 * u(rng));
    for (int p = 0; p < parts; ++p) {
      out.push_back({{cx + 0.15 * (u(rng) - 0.5), cy + 0.15 * (u(rng) - 0.5)}, 1.0 + 3.0 * u(rng)});
    }
  }
  return out;
}

/// Wheel odometry that over-reports travel by `scale_error` and adds a yaw bias per
/// metre, integrated from the true increments (what a real base does).
inline std::vector<OdometrySample> DriftingOdometry(const std::vector<OdometrySample>& truth,
                                                    const Pose2& T_world_odom_start,
                                                    double scale_error, double yaw_bias_rad_per_m) {
  std::vector<OdometrySample> out = truth;
  if (truth.empty()) return out;
  Pose2 odom = T_world_odom_start;
  out[0].T_world_robot = odom;
  for (std::size_t k = 1; k < truth.size(); ++k) {
    Pose2 step = Between(truth[k - 1].T_world_robot, truth[k].T_world_robot);
    const double d = std::hypot(step.x_m, step.y_m);
    step.x_m *= 1.0 + scale_error;
    step.y_m *= 1.0 + scale_error;
    step.yaw_rad += yaw_bias_rad_per_m * d;
    odom = odom * step;
    out[k].T_world_robot = odom;
  }
  return out;
}

/// True pose at `stamp` by interpolation of the ground-truth samples.
inline Pose2 TruePoseAt(const std::vector<OdometrySample>& truth, TimestampNs stamp) {
  if (stamp <= truth.front().stamp_ns) return truth.front().T_world_robot;
  for (std::size_t k = 1; k < truth.size(); ++k) {
    if (truth[k].stamp_ns >= stamp) {
      const double t = static_cast<double>(stamp - truth[k - 1].stamp_ns) /
                       static_cast<double>(truth[k].stamp_ns - truth[k - 1].stamp_ns);
      return Interpolate(truth[k - 1].T_world_robot, truth[k].T_world_robot, t);
    }
  }
  return truth.back().T_world_robot;
}

struct ImagedPass {
  std::vector<Keyframe> keyframes;         ///< anchored at odometry poses
  std::vector<Pose2> T_world_anchor_true;  ///< per keyframe
};

/// Simulates `path` over `scene` with drifting odometry and images it into tiles.
inline ImagedPass ImagePass(const Config& config, const SyntheticPath& path,
                            const std::vector<Scatterer>& scene, std::uint64_t seed,
                            double scale_error = 0.0, double yaw_bias_rad_per_m = 0.0,
                            const Pose2& odom_offset = Pose2{}) {
  EchoModel model;
  model.noise_std = 0.002;
  SyntheticRun run = SimulateRun(config, path, scene, model, seed);
  const std::vector<OdometrySample> truth = run.odometry;
  run.odometry = DriftingOdometry(truth, odom_offset * truth.front().T_world_robot, scale_error,
                                  yaw_bias_rad_per_m);
  ImagingFrontend frontend(config);
  std::size_t o = 0;
  for (const RadarScan& scan : run.scans) {
    while (o < run.odometry.size() && run.odometry[o].stamp_ns <= scan.stamp_ns) {
      frontend.AddOdometry(run.odometry[o++]);
    }
    frontend.AddScan(scan);
  }
  while (o < run.odometry.size()) frontend.AddOdometry(run.odometry[o++]);
  frontend.Finish();
  ImagedPass pass;
  pass.keyframes = frontend.TakeKeyframes();
  for (const Keyframe& k : pass.keyframes) {
    // The anchor is rigidly attached to the robot at the tile's first scan.
    pass.T_world_anchor_true.push_back(TruePoseAt(truth, k.stamp_ns) *
                                       Between(k.T_world_robot, k.T_world_anchor));
  }
  return pass;
}

/// Out 8 m along a cluttered corridor of point scatterers (seed 7) and back the same way 5 cm
/// aside, the return pass with drifting odometry: the revisit the acceptance tests match.
struct CorridorRevisit {
  ImagedPass out;
  ImagedPass back;
};
inline CorridorRevisit ImageClutteredCorridorRevisit(const Config& config) {
  SyntheticPath out;
  out.length_m = 8.0;
  out.radar_rate_hz = 60.0;
  SyntheticPath back = out;
  back.start = {8.0, 0.05, M_PI};
  back.start_stamp_ns = out.start_stamp_ns + SecondsToNs(60);
  const auto scene = ClutterScene(7);
  return {ImagePass(config, out, scene, 1),
          ImagePass(config, back, scene, 2, 0.01, 0.003, Pose2{0.05, -0.03, 0.01})};
}

}  // namespace uwbsar::testing
