// uwbsar: pose-graph SLAM with UWB synthetic-aperture radar. See README.md.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "core/errors.h"
#include "core/interrupt_cleanup.h"
#include "core/log.h"
#include "tools/commands.h"

int main(int argc, char** argv) {
  using namespace uwbsar;
  using namespace uwbsar::tools;
  InstallInterruptCleanup();  // before any thread starts: they inherit the blocked signals
  CLI::App app{
      "uwbsar - pose-graph SLAM with UWB synthetic-aperture radar.\n"
      "Exit codes: 0 success, 1 internal or I/O failure, 2 bad command line,\n"
      "3 bad input file or configuration (the message names the file and field)."};
  app.require_subcommand(1);
  // Global options are accepted before or after the subcommand (`uwbsar run --config F`):
  // a subcommand hands the options it does not know to the app.
  app.fallthrough();
  GlobalOptions globals;
  // A path that is not a regular file (a folder, /dev/zero) is bad input, exit 3, refused by the
  // loader with one line (core/bounded_file.h); only a path that does not exist is exit 2.
  app.add_option("--config", globals.config_path, "YAML configuration (default: built-in)")
      ->check(CLI::ExistingPath);
  app.add_flag("-q,--quiet", globals.quiet, "Only print errors");
  app.add_flag("-v,--verbose", globals.verbose, "Print debug messages");
  app.parse_complete_callback([&] {
    SetLogLevel(globals.quiet ? LogLevel::kError
                              : (globals.verbose ? LogLevel::kDebug : LogLevel::kInfo));
    LoadGlobalConfig(&globals);
  });

  AddConfigCommand(app, globals);
  AddImageCommand(app, globals);
  AddDemoCommand(app, globals);
  AddOptimizeCommand(app, globals);
  AddCalibrateCommand(app, globals);
  AddLoopsCommand(app, globals);
  AddMatchCommand(app, globals);
  AddDetectorsCommand(app, globals);
  AddMapCommand(app, globals);
  AddInfoCommand(app, globals);
  AddSimulateCommand(app, globals);
  AddCompareCommand(app, globals);
  AddExportPcdCommand(app, globals);
  AddRunCommand(app, globals);
  AddMergeCommand(app, globals);
  AddLocalizeCommand(app, globals);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  } catch (const InputError& e) {
    std::cerr << "uwbsar: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "uwbsar: error: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitOk;
}
