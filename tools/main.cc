// uwbsar: pose-graph SLAM with UWB synthetic-aperture radar. See README.md.
#include <malloc.h>

#include <CLI/CLI.hpp>
#include <cstring>
#include <exception>
#include <iostream>

#include "core/errors.h"
#include "core/interrupt_cleanup.h"
#include "core/log.h"
#include "tools/commands.h"

namespace {

/// The first word of the command line that is neither an option nor --config's value: what
/// the user meant as the subcommand ("" when there is none).
std::string FirstWord(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--config") == 0) {
      ++i;
    } else if (argv[i][0] != '-') {
      return argv[i];
    }
  }
  return {};
}

/// Every error in one style, on one line: "uwbsar: error: <what>". CLI11's own form
/// ("<what>\nRun with --help for more information.") is replaced; an unknown subcommand is
/// named (CLI11 says "A subcommand is required").
int ReportParseError(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  const std::string word = FirstWord(argc, argv);
  std::string what = e.what();
  if (!word.empty() && app.get_subcommands().empty()) {
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) known = known || sub->check_name(word);
    if (!known) what = "unknown subcommand '" + word + "'";
  }
  std::cerr << "uwbsar: error: " << what << " (see uwbsar --help)\n";
  return uwbsar::tools::kExitUsage;
}

}  // namespace

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
  AddCheckCommand(app, globals);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return ReportParseError(app, e, argc, argv);
  } catch (const InputError& e) {
    std::cerr << "uwbsar: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "uwbsar: error: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitOk;
}
