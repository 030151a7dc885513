// `uwbsar run --config config/robot.yaml [--out DIR]`: live SLAM on the robot
// (slam/live/live_runner.h). SIGINT/SIGTERM finish the run cleanly: drivers stop, the
// graph is solved once more, final outputs are written, exit 0.
// `--emulate` replaces the hardware by emulated devices on pseudo-terminals that play
// a simulated depart-and-return run in the bundled seed_hall room or in --map
// (slam/live/live_emulation.h); the run ends with it.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <optional>

#include "core/interrupt_cleanup.h"
#include "slam/app_config.h"
#include "slam/jobs/saved_session.h"
#include "slam/live/live_emulation.h"
#include "slam/live/live_runner.h"
#include "tools/commands.h"

namespace uwbsar::tools {

std::string BundledMap();  // cmd_demo.cc

namespace {
std::atomic<bool> g_stop{false};
extern "C" void OnStopSignal(int) { g_stop = true; }

struct RunOptions {
  std::string out_dir = "out/run";
  std::string recording;
  bool emulate = false;
  double speed = 1.0;
  double duration_s = 0.0;
  std::uint64_t seed = 1;
  std::string source = "serial";
  std::string map_path;     ///< --emulate: the map to simulate in
  std::string localize_in;  ///< a saved session: localise in it instead of mapping
  bool overwrite = false;   ///< replace a saved map that --out holds
};

void AddRunOptions(CLI::App* cmd, RunOptions* opts) {
  cmd->add_option("--out", opts->out_dir, "Output folder (snapshots, final outputs, live.json)")
      ->capture_default_str()
      ->check(OutputPath("--out"));
  cmd->add_option("--recording", opts->recording,
                  "Recording bag directory (default: <out>/rosbag2_<date>-<time>)")
      ->check(OutputPath("--recording"));
  cmd->add_option("--source", opts->source,
                  "serial: the robot's LT102 radars, Kobuki base and GPIO (live.*); ros2: a ROS 2 "
                  "robot's radar and odometry topics over DDS, results published for RViz2 (dds.*)")
      ->check(CLI::IsMember({"serial", "ros2"}))
      ->capture_default_str();
  cmd->add_flag("--emulate", opts->emulate,
                "Emulated devices on pseudo-terminals playing a simulated depart-and-return run");
  cmd->add_option("--speed", opts->speed, "--emulate: playback speed (1 = real time)")
      ->check(CheckPositiveFinite, "finite > 0")
      ->check(CLI::Range(0.1, 20.0))
      ->capture_default_str();
  cmd->add_option("--duration", opts->duration_s, "--emulate: play only this many seconds (> 0)")
      ->check(CheckPositiveFinite, "finite > 0");
  cmd->add_option("--seed", opts->seed, "--emulate: simulation seed")
      ->check(CheckSeed, "integer 0..2^64-1")
      ->capture_default_str();
  cmd->add_option("--map", opts->map_path,
                  "--emulate: map_server map to simulate in (default: the bundled seed_hall)")
      ->check(InputFile());
  cmd->add_option("--localize-in", opts->localize_in,
                  "Saved session (folder or session.uwbsar): localise in it instead of mapping "
                  "(the map is not changed; outputs as `localize`, pose and map->odom on /tf)");
  cmd->add_flag("--overwrite", opts->overwrite,
                "Replace the saved map (session.uwbsar) that --out already holds (refused "
                "otherwise)");
}

/// What the run did, and the odometry calibration it applied (once: PrintMapSummary prints
/// it with a map's summary).
void PrintRunResult(const slam::LiveRunResult& result, const Config& config,
                    const std::string& out_dir, const GlobalOptions& globals) {
  std::printf(
      "live run: %lld scans, %lld odometry, %lld recorded messages, %lld dropped from "
      "processing\n",
      result.scans_received, result.odometry_received, result.recorded_messages,
      result.dropped_from_processing);
  std::printf("scan-to-tile latency p50 %.1f ms, p99 %.1f ms, max %.1f ms over %lld scans\n",
              result.latency_p50_ms, result.latency_p99_ms, result.latency_max_ms,
              result.latency_samples);
  for (const auto& [kind, count] : result.faults) {
    std::printf("fault %s: %lld\n", kind.c_str(), count);
  }
  std::printf("recording: %s\n", result.recording_path.c_str());
  if (result.localized) {
    const slam::LocalizeRun& l = result.localize;
    std::printf("localised %zu keyframes in the saved map; ", l.keyframes.size());
    if (l.first_fix >= 0) {
      std::printf("first fix after %.2f m (%.1f s of log)\n", l.first_fix_path_m,
                  l.first_fix_time_s);
    } else {
      std::printf("never placed in the map: lost\n");
    }
    std::printf("outputs: %s/trajectory.tum, localize.csv, summary.json, live.json\n",
                out_dir.c_str());
  } else if (result.run.slam && !result.run.slam->keyframes().empty()) {
    PrintMapSummary(result.run, result.outputs, out_dir, globals);
    return;
  }
  PrintOdometryCalibration(config, globals);
}

void Run(const RunOptions& opts, const GlobalOptions& globals) {
  Config config = LoadConfigFor(globals);
  // SIGINT/SIGTERM finish the run cleanly (core/interrupt_cleanup.h's watcher calls this;
  // the plain handler serves callers that did not install the watcher).
  SetInterruptHandler([] { g_stop = true; });
  std::signal(SIGINT, OnStopSignal);
  std::signal(SIGTERM, OnStopSignal);
  slam::LiveRunOptions options;
  options.out_dir = opts.out_dir;
  options.recording_dir = opts.recording;
  options.source = opts.source;
  if (opts.emulate && opts.source != "serial") {
    throw InputError("--emulate plays serial devices: it needs --source serial");
  }
  options.stop = &g_stop;
  options.quiet = globals.quiet;
  options.localize_in = opts.localize_in;
  options.overwrite = opts.overwrite;
  if (!opts.localize_in.empty()) slam::RefuseMapFolderForLocalize(opts.out_dir);  // its own words
  RefuseOutputsOnInputs(
      globals, {{"--out", opts.out_dir}, {"--recording", opts.recording}},
      {{"the --map file",
        opts.emulate ? (opts.map_path.empty() ? BundledMap() : opts.map_path) : ""},
       opts.localize_in.empty() ? slam::CommandInput{}
                                : SessionInput("the --localize-in session", opts.localize_in)});
  // Locked and checked before any emulated device is made inside it.
  const FolderLock out_lock = slam::LockLiveOutputFolder(options);
  std::optional<slam::LiveEmulation> emulation;
  if (opts.emulate) {
    slam::EmulationOptions emulation_options;
    emulation_options.map_yaml = opts.map_path.empty() ? BundledMap() : opts.map_path;
    emulation_options.seed = opts.seed;
    emulation_options.speed = opts.speed;
    emulation_options.duration_s = opts.duration_s;
    emulation.emplace(emulation_options, &config, &options, &g_stop);
  }
  slam::LiveRunResult result = slam::RunLive(config, std::move(options));
  if (emulation) emulation->Finish();
  if (!globals.quiet) PrintRunResult(result, config, opts.out_dir, globals);
}

}  // namespace

void AddRunCommand(CLI::App& app, const GlobalOptions& globals) {
  auto opts = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand(
      "run", "Live SLAM on the robot: LT102 radars, Kobuki odometry, GPIO, recording");
  AddRunOptions(cmd, opts.get());
  cmd->callback([opts, &globals] { Run(*opts, globals); });
}

}  // namespace uwbsar::tools
