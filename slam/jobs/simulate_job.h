// The job behind `uwbsar simulate`: a simulated recording of the robot driving a route in a
// map_server map (drivers/sim/sim_stream.h), written as a ROS 2 bag like the real robot's
// with its ground truth (drivers/sim/sim_bag_writer.h), and optionally as a text log
// (drivers/sim/sim_recorder.h). The same configuration, map, route and seeds give the same
// bytes.
#pragma once

#include <cstdint>
#include <string>

#include "drivers/sim/scene_change.h"
#include "drivers/sim/sim_bag_writer.h"
#include "slam/app_config.h"

namespace uwbsar::slam {

struct SimulateJobOptions {
  std::string map_yaml;                 ///< the map_server map to drive in
  std::string route = "depart-return";  ///< built-in route name or waypoints file
  std::string bag_dir;                  ///< the bag folder to create (must not exist)
  std::string storage = "sqlite3";      ///< sqlite3 or mcap
  std::string targets_path;             ///< extra point targets (LoadPointTargets); empty: none
  std::string text_log;          ///< also write odometry and scans as a text log here; empty: not
  std::uint64_t seed = 1;        ///< the run's noise and odometry errors
  std::uint64_t scene_seed = 1;  ///< the scene's scatterers (slam/scene_simulation.h)
  bool progress = false;         ///< draw a progress bar on stderr (slam/progress.h)
};

struct SimulateJobResult {
  std::string route_name;
  double route_length_m = 0.0;
  double route_duration_s = 0.0;
  sim::SimBagSummary summary;     ///< message counts, last odometry and ground truth
  sim::SceneChange scene_change;  ///< simulator.scene_change's edits (its grid left empty)
  int people = 0;                 ///< people walking past (simulator.people)
  double seconds = 0.0;           ///< wall time of the scenario and the bag
};

/// Loads the point targets, checks every output before the work (InputError: the bag folder
/// or an interrupted attempt BAG.partial exists, the folders are not writable), simulates
/// into `bag_dir` (with `bag_dir`/ground_truth.tum), then writes the text log from a second
/// stream with the same seed. Ctrl-C or a failure (disk full) leaves no BAG.partial and no
/// bag behind.
SimulateJobResult RunSimulateJob(const Config& config, const SimulateJobOptions& options);

}  // namespace uwbsar::slam
