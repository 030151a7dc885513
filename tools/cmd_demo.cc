// `uwbsar demo`: the embedded default. Simulates the paper's experiment (a
// depart-and-return pass with wheel-odometry drift) in the project's own seed_hall room
// (config/maps/seed_hall, drawn by our generator after the paper's description) or in
// any map_server map given with --map, maps it with the full pipeline, compares with
// the ground truth and prints a five-line summary.
#include <cstdio>
#include <filesystem>

#include "slam/app_config.h"
#include "slam/jobs/saved_session.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/session_capture.h"
#include "tools/commands.h"

namespace uwbsar::tools {

/// The project's bundled seed_hall map: next to the working directory when run from
/// the repository (make demo), else from the source tree the binary was built in.
std::string BundledMap() {
  const std::string relative = "config/maps/seed_hall/seed_hall.yaml";
  if (std::filesystem::exists(relative)) return relative;
  return std::string(UWBSAR_SOURCE_DIR) + "/" + relative;
}

void AddDemoCommand(CLI::App& app, const GlobalOptions& globals) {
  struct Options {
    std::string out_dir = "out/demo";
    std::uint64_t seed = 1;
    std::string map_path;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "demo", "Simulate the paper's depart-and-return run, map it and compare with ground truth");
  cmd->add_option("--out", opts->out_dir, "Output folder")
      ->capture_default_str()
      ->check(OutputPath("--out"));
  cmd->add_option("--seed", opts->seed, "Simulation seed")
      ->check(CheckSeed, "integer 0..2^64-1")
      ->capture_default_str();
  cmd->add_option("--map", opts->map_path,
                  "map_server map (YAML + PGM) to simulate in; default: the bundled "
                  "config/maps/seed_hall/seed_hall.yaml")
      ->check(InputFile());
  cmd->callback([opts, &globals] {
    const Config config = LoadConfigFor(globals);
    const std::string map = opts->map_path.empty() ? BundledMap() : opts->map_path;
    RefuseOutputsOnInputs(globals, {{"--out", opts->out_dir}}, {{"the --map file", map}});
    slam::MapOutputStage stage(opts->out_dir);
    slam::RefuseToReplaceSavedMap(opts->out_dir, {}, false, "give another --out");
    slam::MapRun run =
        slam::MapSimulation(config, map, "depart-return", opts->seed, nullptr, !globals.quiet);
    slam::SaveSessionWithOutputs(&stage, run);  // `map --resume DIR` extends the demo's map
    const slam::MapOutputs outputs = stage.Commit(run);
    PrintMapSummary(run, outputs, opts->out_dir, globals);
  });
}

}  // namespace uwbsar::tools
