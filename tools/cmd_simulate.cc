// `uwbsar simulate`: a simulated recording of the robot driving a route in a
// map_server map, written as a ROS 2 bag like the real robot's, with ground truth:
//   BAG/                    the bag (metadata.yaml + BAG_0.db3 or BAG_0.mcap): radar scans on
//                           radars[].topic, wheel odometry, ground truth, optional laser
//   BAG/ground_truth.tum    true poses (TUM: t x y z qx qy qz qw) at ground_truth_rate_hz
// and, with --text-log FILE, the odometry and scans as a plain text log too.
// Reproducible: the same configuration, map, route and seed give the same bytes.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "core/interrupt_cleanup.h"
#include "drivers/sim/sim_bag_writer.h"
#include "drivers/sim/sim_recorder.h"
#include "drivers/sim/sim_stream.h"
#include "slam/app_config_io.h"
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
  std::string scene_seed;  ///< empty: the seed
  bool laser = false;
};

void RunSimulate(const SimulateOptions& o, const GlobalOptions& globals) {
  Config config = LoadConfigFor(globals);
  if (o.laser) config.simulator.laser.enabled = true;
  const std::vector<PointTargetConfig> targets =
      o.targets_path.empty() ? std::vector<PointTargetConfig>{} : LoadPointTargets(o.targets_path);
  // Every output is checked before the work: the bag folder's parent is writable and
  // neither the bag nor an interrupted attempt (BAG.partial) is in the way.
  namespace fs = std::filesystem;
  const std::string bag_dir = fs::path(o.out_dir).lexically_normal().string();
  const std::string partial =
      (bag_dir.back() == '/' ? bag_dir.substr(0, bag_dir.size() - 1) : bag_dir) + ".partial";
  std::error_code ec;
  if (fs::exists(bag_dir, ec)) throw InputError(bag_dir + ": exists already, not overwriting");
  if (fs::exists(partial, ec)) {
    throw InputError(partial + ": exists (an interrupted recording?); remove it first");
  }
  const std::string parent = fs::path(partial).parent_path().string();
  pipeline::CheckOutputFolder(parent.empty() ? "." : parent);
  if (!o.text_log_path.empty()) pipeline::CheckOutputFile(o.text_log_path);
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t scene_seed = o.scene_seed.empty() ? o.seed : std::stoull(o.scene_seed);
  const sim::SimScenario scenario =
      sim::MakeScenario(config, o.map_path, o.route, scene_seed, targets);
  sim::SimStream stream(config, scenario, o.seed);
  sim::SimBagSummary summary;
  {
    const RemoveOnInterrupt guard(partial);  // Ctrl-C leaves no BAG.partial behind
    try {
      summary =
          sim::WriteSimBag(&stream, config, o.out_dir, o.storage, o.out_dir + "/ground_truth.tum");
    } catch (...) {
      // A failed simulation (disk full) leaves nothing that blocks a retry (neither existed
      // before: checked above).
      fs::remove_all(partial, ec);
      fs::remove_all(bag_dir, ec);
      throw;
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.text_log_path.empty()) {
    sim::SimStream again(config, scenario, o.seed);  // same seed: the same messages
    WriteTextLog(o.text_log_path, sim::ToTextLog(sim::RecordStream(&again)));
  }
  if (globals.quiet) return;
  const double length = scenario.trajectory.length_m();
  const Pose2& odom = summary.last_odometry.T_world_robot;
  const Pose2& truth = summary.last_ground_truth.T_world_robot;
  std::printf(
      "simulated route '%s': %.2f m in %.1f s: %lld radar scans, %lld odometry, %lld ground "
      "truth, %lld laser scans\n"
      "took %.2f s (%.3f s per metre); odometry at the end is off by %.3f m and %.2f deg\n"
      "wrote %s (%s) and %s/ground_truth.tum%s%s\n",
      scenario.route.name.c_str(), length, scenario.trajectory.duration_s(), summary.radar_scans,
      summary.odometry, summary.ground_truth, summary.laser_scans, seconds,
      length > 0 ? seconds / length : 0.0, Distance(odom, truth),
      NormalizeAngle(odom.yaw_rad - truth.yaw_rad) * 180.0 / M_PI, o.out_dir.c_str(),
      o.storage.c_str(), o.out_dir.c_str(), o.text_log_path.empty() ? "" : ", ",
      o.text_log_path.c_str());
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
      ->check(CLI::ExistingFile);
  cmd->add_option("--route", o->route,
                  "depart-return, loop, or a waypoints file (lines 'x_m y_m', world frame)")
      ->capture_default_str();
  cmd->add_option("--out", o->out_dir, "Bag folder to create (must not exist)")->required();
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
  cmd->add_option("--targets", o->targets_path,
                  "Point targets file (YAML: point_targets: [{x_m, y_m, rcs_m2}, ...])")
      ->check(CLI::ExistingFile);
  cmd->add_option("--text-log", o->text_log_path,
                  "Also write odometry and scans as a plain text log to this file");
  cmd->add_flag("--laser", o->laser, "Also simulate a 2-D LiDAR on simulator.laser.topic");
  cmd->callback([o, &globals] { RunSimulate(*o, globals); });
}

}  // namespace uwbsar::tools
