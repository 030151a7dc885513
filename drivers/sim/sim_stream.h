// The simulated recording as a time-ordered message stream: ground-truth poses,
// wheel odometry, the scans of every radar and (optionally) laser scans, each
// at its own rate from the trajectory's start to its end. Producing the stream
// is separate from writing it (text log, TUM, ROS 2 bag: drivers/sim/sim_recorder.h),
// so tests can consume it in memory.
//
// Determinism: every random draw comes from a generator derived from the seed
// and the message's source and index, so the same configuration, map, route and
// seed give the same messages, bit for bit.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/types.h"
#include "drivers/sim/base_odometry.h"
#include "drivers/sim/laser_simulator.h"
#include "drivers/sim/radar_simulator.h"
#include "drivers/sim/scene_change.h"
#include "drivers/sim/sim_environment.h"
#include "drivers/sim/sim_settings.h"
#include "drivers/sim/trajectory.h"
#include "drivers/sim/walking_people.h"

namespace uwbsar::sim {

struct SimMessage {
  enum class Kind { kGroundTruth, kOdometry, kRadarScan, kLaserScan };
  Kind kind = Kind::kGroundTruth;
  TimestampNs stamp_ns = 0;
  OdometrySample pose;  ///< kGroundTruth: the true pose and velocities; kOdometry: the base's
  RadarScan scan;       ///< kRadarScan; scan.sensor_id indexes Config::radars
  SimLaserScan laser;   ///< kLaserScan
};

/// Everything a run needs besides the configuration: the world and the motion.
struct SimScenario {
  std::shared_ptr<const SimEnvironment> environment;
  Route route;
  Trajectory trajectory;
  std::vector<SceneEdit> scene_edits;  ///< simulator.scene_change's edits of the map (or none)
};

/// Loads the map, resolves the route (built-in name or waypoints file), plans the motion,
/// changes the building when simulator.scene_change.seed is set (drivers/sim/scene_change.h:
/// the scene's scatterers still come from `seed`) and checks the route's clearance in it.
/// `extra_targets` are added to the configured point targets. Throws InputError on bad input
/// (map, route, collision).
SimScenario MakeScenario(const SimSettings& config, const std::string& map_yaml,
                         const std::string& route_spec, std::uint64_t seed,
                         const std::vector<PointTargetConfig>& extra_targets = {});

/// The true bias (rad/s) of the base's gyro in the run of `seed` (profile kobuki_gyro; empty
/// with wheel) at each of `times_s` (ascending, seconds from the run's start): the turn-on bias
/// at 0, then as it walked, replayed from the run's own generator (the draws do not depend on
/// the motion). For tests and benchmarks that compare a run's estimated bias with the truth.
std::vector<double> TrueGyroBiasRadps(const SimOdometryConfig& config, std::uint64_t seed,
                                      const std::vector<double>& times_s);

class SimStream {
 public:
  /// Uses config.simulator (rates, odometry, radar and laser models) and config.radars.
  SimStream(const SimSettings& config, const SimScenario& scenario, std::uint64_t seed);

  /// The next message in time order (ties: ground truth, odometry, radars in order,
  /// laser); false once the run is over.
  bool Next(SimMessage* msg);

  TimestampNs start_ns() const { return start_ns_; }
  /// Time from the first to the last message: the motion, rounded up to whole odometry periods.
  double duration_s() const { return end_s_; }
  /// Cells lit by the latest scan of radar `sensor_id` (for metrics and tests).
  const std::vector<int>& lit_cells(int sensor_id) const { return radars_[sensor_id]->lit_cells(); }
  /// The people walking past (simulator.people: as many as found a free path).
  const std::vector<WalkingPerson>& people() const { return people_; }

 private:
  /// One periodic source: message k is at k / rate_hz seconds.
  struct Clock {
    double rate_hz = 1.0;
    long long next = 0;
    long long count = 0;
  };
  TimestampNs StampOf(const Clock& clock) const;
  double TimeOf(const Clock& clock) const {
    return static_cast<double>(clock.next) / clock.rate_hz;
  }

  SimSettings config_;
  SimScenario scenario_;
  std::uint64_t seed_;
  TimestampNs start_ns_ = 0;
  double end_s_ = 0.0;
  std::vector<std::unique_ptr<RadarSimulator>> radars_;
  std::vector<Pose2> T_robot_sensor_;
  std::vector<WalkingPerson> people_;  ///< simulator.people, from the run's seed
  GridRayCaster laser_caster_;
  BaseOdometrySimulator odometry_;
  Clock ground_truth_clock_, odometry_clock_, radar_clock_, laser_clock_;
  int next_radar_ = 0;  ///< radars of the current frame already emitted
};

}  // namespace uwbsar::sim
