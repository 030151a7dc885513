// `uwbsar simulate`: a simulated recording of the robot driving a route in a
// map_server map, written as a ROS 2 bag like the real robot's, with ground truth:
//   BAG/                    the bag (metadata.yaml + BAG_0.db3 or BAG_0.mcap): radar scans on
//                           radars[].topic, wheel odometry, ground truth, optional laser
//   BAG/ground_truth.tum    true poses (TUM: t x y z qx qy qz qw) at ground_truth_rate_hz
// and, with --text-log FILE, the odometry and scans as a plain text log too.
// Reproducible: the same configuration, map, route and seed give the same bytes
// (slam/jobs/simulate_job.h).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "slam/app_config.h"
#include "slam/jobs/simulate_job.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

struct SimulateOptions {
  std::string map_path;
  std::string route = "depart-return";
  std::string out_dir;
  std::string storage = "sqlite3";
  std::string targets_path;
  std::string text_log_path;
  std::uint64_t seed = 1;
  std::string scene_seed;   ///< empty: the seed
  std::string change_seed;  ///< empty: simulator.scene_change.seed
  int people = -1;          ///< < 0: simulator.people.count
  bool laser = false;
};

void RunSimulate(const SimulateOptions& o, const GlobalOptions& globals) {
  Config config = LoadConfigFor(globals);
  RefuseOutputsOnInputs(globals, {{"--out", o.out_dir}, {"--text-log", o.text_log_path}},
                        {{"the --map file", o.map_path},
                         {"the --route file", std::filesystem::exists(o.route) ? o.route : ""},
                         {"the --targets file", o.targets_path}});
  if (o.laser) config.simulator.laser.enabled = true;
  if (!o.change_seed.empty()) config.simulator.scene_change.seed = std::stoull(o.change_seed);
  if (o.people >= 0) config.simulator.people.count = o.people;
  slam::SimulateJobOptions options;
  options.map_yaml = o.map_path;
  options.route = o.route;
  options.bag_dir = o.out_dir;
  options.storage = o.storage;
  options.targets_path = o.targets_path;
  options.text_log = o.text_log_path;
  options.seed = o.seed;
  options.scene_seed = o.scene_seed.empty() ? o.seed : std::stoull(o.scene_seed);
  options.progress = !globals.quiet;
  const slam::SimulateJobResult result = slam::RunSimulateJob(config, options);
  if (globals.quiet) return;
  const sim::SimBagSummary& summary = result.summary;
  const double length = result.route_length_m;
  const double seconds = result.seconds;
  const Pose2& odom = summary.last_odometry.T_world_robot;
  const Pose2& truth = summary.last_ground_truth.T_world_robot;
  std::printf(
      "simulated route '%s': %.2f m in %.1f s: %lld radar scans, %lld odometry, %lld ground "
      "truth, %lld laser scans\n"
      "took %.2f s (%.3f s per metre); odometry at the end is off by %.3f m and %.2f deg\n"
      "wrote %s (%s) and %s/ground_truth.tum%s%s\n",
      result.route_name.c_str(), length, result.route_duration_s, summary.radar_scans,
      summary.odometry, summary.ground_truth, summary.laser_scans, seconds,
      length > 0 ? seconds / length : 0.0, Distance(odom, truth),
      NormalizeAngle(odom.yaw_rad - truth.yaw_rad) * 180.0 / M_PI, o.out_dir.c_str(),
      o.storage.c_str(), o.out_dir.c_str(), o.text_log_path.empty() ? "" : ", ",
      o.text_log_path.c_str());
  if (config.simulator.scene_change.seed) {
    using Kind = sim::SceneEdit::Kind;
    const sim::SceneChange& c = result.scene_change;
    std::printf(
        "scene changed (change seed %llu): %d objects added, %d removed, %d moved; %d doors "
        "closed, %d opened\n",
        static_cast<unsigned long long>(*config.simulator.scene_change.seed),
        c.Count(Kind::kObjectAdded), c.Count(Kind::kObjectRemoved), c.Count(Kind::kObjectMoved),
        c.Count(Kind::kDoorClosed), c.Count(Kind::kDoorOpened));
  }
  if (config.simulator.people.count > 0) {
    std::printf("%d of %d people walking past\n", result.people, config.simulator.people.count);
  }
}

}  // namespace

void AddSimulateCommand(CLI::App& app, const GlobalOptions& globals) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Simulate a recording: the robot drives a route in a map_server map; writes a ROS 2 bag "
      "(radar scans, wheel odometry, ground truth) and BAG/ground_truth.tum");
  cmd->add_option("--map", o->map_path,
                  "map_server map (YAML + PGM), e.g. config/maps/seed_hall/seed_hall.yaml")
      ->required()
      ->check(InputFile());
  cmd->add_option("--route", o->route,
                  "depart-return, loop, or a waypoints file (lines 'x_m y_m', world frame)")
      ->capture_default_str();
  cmd->add_option("--out", o->out_dir, "Bag folder to create (must not exist)")
      ->required()
      ->check(OutputPath("--out"));
  cmd->add_option("--storage", o->storage, "Bag storage: sqlite3 (Humble) or mcap")
      ->check(CLI::IsMember({"sqlite3", "mcap"}))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed (same seed, same bytes)")
      ->check(CheckSeed, "integer 0..2^64-1")
      ->capture_default_str();
  cmd->add_option(
         "--scene-seed", o->scene_seed,
         "Seed of the scene alone (the scatterers of the occupied cells; default: --seed): "
         "runs with one scene seed and different seeds revisit the same building")
      ->check(CheckSeed, "integer 0..2^64-1");
  cmd->add_option("--change-seed", o->change_seed,
                  "Seed of a changed building (simulator.scene_change): objects added, removed "
                  "and moved, doors closed and opened; the map file stays the day-1 building")
      ->check(CheckSeed, "integer 0..2^64-1");
  cmd->add_option("--people", o->people,
                  "People walking past during the run (simulator.people.count)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--targets", o->targets_path,
                  "Point targets file (YAML: point_targets: [{x_m, y_m, rcs_m2}, ...])")
      ->check(InputFile());
  cmd->add_option("--text-log", o->text_log_path,
                  "Also write odometry and scans as a plain text log to this file")
      ->check(OutputPath("--text-log"));
  cmd->add_flag("--laser", o->laser, "Also simulate a 2-D LiDAR on simulator.laser.topic");
  cmd->callback([o, &globals] { RunSimulate(*o, globals); });
}

}  // namespace uwbsar::tools
