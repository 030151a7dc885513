#include "drivers/sim/sim_stream.h"

#include <cmath>
#include <optional>

#include "imaging/sensor_geometry.h"

namespace uwbsar::sim {
namespace {

// Seed streams: the environment uses its own (sim_environment.cc).
constexpr std::uint64_t kOdometryStream = 1;
constexpr std::uint64_t kLaserStream = 2;
constexpr std::uint64_t kGyroStream = 3;
constexpr std::uint64_t kPeopleStream = 4;
constexpr std::uint64_t kRadarStream = 16;  // + sensor id

long long CountFor(double duration_s, double rate_hz) {
  return static_cast<long long>(std::floor(duration_s * rate_hz + 1e-9)) + 1;
}

}  // namespace

std::vector<double> TrueGyroBiasRadps(const SimOdometryConfig& config, std::uint64_t seed,
                                      const std::vector<double>& times_s) {
  if (config.profile != "kobuki_gyro") return {};
  // As BaseOdometrySimulator steps it: one step per odometry period after the first sample.
  GyroModel gyro(config.gyro, 0.0, DeriveSeed(seed, kGyroStream));
  const double period_s = 1.0 / config.rate_hz;
  std::vector<double> bias;
  long long steps = 0;
  for (double t : times_s) {
    for (; steps < std::llround(t / period_s); ++steps) gyro.Step(period_s, 0.0);
    bias.push_back(gyro.bias_radps());
  }
  return bias;
}

SimScenario MakeScenario(const SimSettings& config, const std::string& map_yaml,
                         const std::string& route_spec, std::uint64_t seed,
                         const std::vector<PointTargetConfig>& extra_targets) {
  SimRadarConfig radar = config.simulator.radar;
  radar.point_targets.insert(radar.point_targets.end(), extra_targets.begin(), extra_targets.end());
  SimScenario scenario;
  OccupancyGrid grid = LoadOccupancyGrid(map_yaml, config.limits.max_map_image_pixels);
  scenario.route =
      ResolveRoute(route_spec, config.simulator.route, config.limits.max_input_file_mb);
  scenario.trajectory = Trajectory::Plan(scenario.route, config.simulator.route);
  const SimSceneChangeConfig& change = config.simulator.scene_change;
  if (change.seed) {
    SceneChange changed = DrawSceneChange(grid, scenario.route.waypoints, change, *change.seed);
    scenario.scene_edits = std::move(changed.edits);
    scenario.environment =
        std::make_shared<const SimEnvironment>(std::move(grid), radar, seed, &changed.grid);
  } else {
    scenario.environment = std::make_shared<const SimEnvironment>(std::move(grid), radar, seed);
  }
  scenario.trajectory.CheckClearance(scenario.environment->grid(),
                                     config.simulator.route.clearance_m);
  return scenario;
}

SimStream::SimStream(const SimSettings& config, const SimScenario& scenario, std::uint64_t seed)
    : config_(config),
      scenario_(scenario),
      seed_(seed),
      start_ns_(SecondsToNs(config.simulator.start_time_s)),
      laser_caster_(scenario.environment->grid()),
      odometry_(config.simulator.odometry, scenario.trajectory.At(0.0),
                DeriveSeed(seed, kOdometryStream), DeriveSeed(seed, kGyroStream)) {
  people_ = PlaceWalkingPeople(scenario.environment->grid(), scenario.route.waypoints,
                               config.simulator.people, DeriveSeed(seed, kPeopleStream));
  for (const RadarConfig& radar : config.radars) {
    const SensorGeometry sensor = SensorGeometry::FromConfig(radar, config.pulse);
    T_robot_sensor_.push_back(sensor.T_robot_sensor);
    radars_.push_back(std::make_unique<RadarSimulator>(*scenario.environment, config.pulse, sensor,
                                                       config.simulator.radar));
  }
  const SimulatorConfig& s = config.simulator;
  // The recording ends on the first odometry sample at or after the end of the motion
  // (the robot stands still by then), so odometry brackets every scan as in a real bag.
  const double odometry_period = 1.0 / s.odometry.rate_hz;
  const double duration =
      std::ceil(scenario.trajectory.duration_s() / odometry_period - 1e-9) * odometry_period;
  end_s_ = duration;
  ground_truth_clock_ = {s.odometry.ground_truth_rate_hz, 0,
                         CountFor(duration, s.odometry.ground_truth_rate_hz)};
  odometry_clock_ = {s.odometry.rate_hz, 0, CountFor(duration, s.odometry.rate_hz)};
  radar_clock_ = {s.radar.rate_hz, 0, radars_.empty() ? 0 : CountFor(duration, s.radar.rate_hz)};
  laser_clock_ = {s.laser.rate_hz, 0, s.laser.enabled ? CountFor(duration, s.laser.rate_hz) : 0};
}

TimestampNs SimStream::StampOf(const Clock& clock) const {
  return start_ns_ + static_cast<TimestampNs>(
                         std::llround(static_cast<double>(clock.next) * 1e9 / clock.rate_hz));
}

bool SimStream::Next(SimMessage* msg) {
  // Pick the source with the earliest pending message; ties go in declaration order.
  Clock* clocks[4] = {&ground_truth_clock_, &odometry_clock_, &radar_clock_, &laser_clock_};
  int best = -1;
  TimestampNs best_stamp = 0;
  for (int i = 0; i < 4; ++i) {
    if (clocks[i]->next >= clocks[i]->count) continue;
    const TimestampNs stamp = StampOf(*clocks[i]);
    if (best < 0 || stamp < best_stamp) {
      best = i;
      best_stamp = stamp;
    }
  }
  if (best < 0) return false;
  Clock& clock = *clocks[best];
  const RobotState truth = scenario_.trajectory.At(TimeOf(clock));
  msg->stamp_ns = best_stamp;
  if (best == 0) {
    msg->kind = SimMessage::Kind::kGroundTruth;
    msg->pose = {best_stamp, truth.T_world_robot, truth.linear_mps, truth.angular_radps};
    ++clock.next;
  } else if (best == 1) {
    msg->kind = SimMessage::Kind::kOdometry;
    // simulator.carried: the steps that end on the carried stretch of route.
    const std::optional<double>& carry_m = config_.simulator.carried.at_path_m;
    const bool carried = carry_m && truth.path_m > *carry_m &&
                         truth.path_m <= *carry_m + config_.simulator.carried.distance_m;
    msg->pose = odometry_.Step(best_stamp, truth, carried);
    ++clock.next;
  } else if (best == 2) {
    const int k = next_radar_;
    msg->kind = SimMessage::Kind::kRadarScan;
    std::mt19937_64 rng(DeriveSeed(seed_, kRadarStream + static_cast<std::uint64_t>(k),
                                   static_cast<std::uint64_t>(clock.next)));
    msg->scan.stamp_ns = best_stamp;
    msg->scan.sensor_id = k;
    msg->scan.samples = radars_[k]->Simulate(truth.T_world_robot * T_robot_sensor_[k], &rng,
                                             PeopleAt(people_, TimeOf(clock)));
    if (++next_radar_ == static_cast<int>(radars_.size())) {
      next_radar_ = 0;
      ++clock.next;
    }
  } else {
    msg->kind = SimMessage::Kind::kLaserScan;
    std::mt19937_64 rng(DeriveSeed(seed_, kLaserStream, static_cast<std::uint64_t>(clock.next)));
    msg->laser = SimulateLaserScan(laser_caster_, truth.T_world_robot, config_.simulator.laser,
                                   &rng, PeopleAt(people_, TimeOf(clock)));
    msg->laser.stamp_ns = best_stamp;
    ++clock.next;
  }
  return true;
}

}  // namespace uwbsar::sim
