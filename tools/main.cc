// uwbsar: pose-graph SLAM with UWB synthetic-aperture radar. See README.md.
#include <malloc.h>

#include <CLI/CLI.hpp>

#include "core/interrupt_cleanup.h"
#include "core/log.h"
#include "tools/commands.h"
#include "tools/usage_error.h"

int main(int argc, char** argv) {
  using namespace uwbsar;
  using namespace uwbsar::tools;
  InstallInterruptCleanup();  // before any thread starts: they inherit the blocked signals
  // Two malloc arenas, not glibc's default of eight per core: the keyframe thread frees the
  // tiles the feeding thread allocated, and with an arena per thread the freed megabytes stayed
  // scattered over arenas, so that resident memory grew with the hours driven (office ring, ten
  // laps: peak 415-478 MiB with the default, 362 MiB with two; no time lost).
  mallopt(M_ARENA_MAX, 2);
  CLI::App app{
      "uwbsar - pose-graph SLAM with UWB synthetic-aperture radar.\n"
      "Exit codes: 0 success, 1 internal or I/O failure or a degenerate result (the message\n"
      "says why and which key changes it), 2 bad command line, 3 bad or missing input file or\n"
      "configuration (the message names the file and field)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "uwbsar " UWBSAR_VERSION);
  // Global options are accepted before or after the subcommand (`uwbsar run --config F`):
  // a subcommand hands the options it does not know to the app.
  app.fallthrough();
  GlobalOptions globals;
  // A path that does not exist is exit 3 (InputPath); one that is not a regular file (a
  // folder, /dev/zero) is refused by the loader with one line (core/bounded_file.h), exit 3.
  app.add_option("--config", globals.config_paths,
                 "YAML configuration (default: built-in); repeat it to merge files in order, "
                 "later keys win (e.g. a robot's file, then a calibration file)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->check(InputPath());
  app.add_flag("-q,--quiet", globals.quiet, "Only print errors");
  app.add_flag("-v,--verbose", globals.verbose, "Also print the per-stage log (debug messages)");
  app.parse_complete_callback([&] {
    SetLogLevel(globals.quiet ? LogLevel::kError
                              : (globals.verbose ? LogLevel::kDebug : LogLevel::kInfo));
    LoadGlobalConfig(&globals);
  });

  // `uwbsar --help` lists the commands in this order: the main job first (try it, map, use
  // the map, live, join maps), then what a robot of one's own needs, the tools around a map,
  // and last the developers' tools, under their own heading.
  AddDemoCommand(app, globals);
  AddMapCommand(app, globals);
  AddLocalizeCommand(app, globals);
  AddRunCommand(app, globals);
  AddMergeCommand(app, globals);
  AddCalibrateCommand(app, globals);
  AddCheckCommand(app, globals);
  AddCompareCommand(app, globals);
  AddInfoCommand(app, globals);
  AddSimulateCommand(app, globals);
  AddExportPcdCommand(app, globals);
  AddConfigCommand(app, globals);
  AddImageCommand(app, globals);
  AddMatchCommand(app, globals);
  AddLoopsCommand(app, globals);
  AddDetectorsCommand(app, globals);
  AddOptimizeCommand(app, globals);
  for (CLI::App* command : app.get_subcommands({})) command->group("Commands");
  for (const char* name : {"image", "match", "loops", "detectors", "optimize"}) {
    app.get_subcommand(name)->group("Developer tools");
  }

  try {
    app.parse(argc, argv);
  } catch (...) {  // every error in one style, on one line (tools/usage_error.h)
    return ReportError(app, argc, argv);
  }
  return kExitOk;
}
