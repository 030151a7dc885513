// The `uwbsar` subcommands. Each Add*Command registers one subcommand on the
// app; its callback throws on failure and main() maps exceptions to exit codes.
// Tools stay thin: they parse flags, call the libraries and write files.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "slam/config.h"

namespace uwbsar::tools {

/// Exit codes, documented in `uwbsar --help`.
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,   ///< an internal or I/O failure
  kExitUsage = 2,     ///< bad command line
  kExitBadInput = 3,  ///< bad input file or configuration (message names it)
};

struct GlobalOptions {
  std::string config_path;  ///< --config; empty = built-in defaults (config/default.yaml)
  bool quiet = false;
  bool verbose = false;
};

/// The configuration named by --config, or the defaults.
Config LoadConfigFor(const GlobalOptions& globals);
/// Creates `dir` (and parents) if needed; throws InputError if it cannot.
void EnsureDirectory(const std::string& dir);

void AddConfigCommand(CLI::App& app, const GlobalOptions& globals);
void AddImageCommand(CLI::App& app, const GlobalOptions& globals);
void AddDemoCommand(CLI::App& app, const GlobalOptions& globals);
void AddOptimizeCommand(CLI::App& app, const GlobalOptions& globals);
void AddLoopsCommand(CLI::App& app, const GlobalOptions& globals);
void AddMatchCommand(CLI::App& app, const GlobalOptions& globals);
void AddDetectorsCommand(CLI::App& app, const GlobalOptions& globals);
void AddMapCommand(CLI::App& app, const GlobalOptions& globals);
void AddInfoCommand(CLI::App& app, const GlobalOptions& globals);
void AddSimulateCommand(CLI::App& app, const GlobalOptions& globals);
void AddCompareCommand(CLI::App& app, const GlobalOptions& globals);
void AddExportPcdCommand(CLI::App& app, const GlobalOptions& globals);
void AddRunCommand(CLI::App& app, const GlobalOptions& globals);

}  // namespace uwbsar::tools
