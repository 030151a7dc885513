// The `uwbsar` subcommands. Each Add*Command registers one subcommand on the
// app; its callback throws on failure and main() maps exceptions to exit codes.
// Tools stay thin: they parse flags, call a job of slam/ (or slam/live) and print what it
// returns; they include slam/ and core/ headers only (cmake/check_layering.py).
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "app/app_config.h"
#include "slam/outputs/output_folder.h"  // EnsureDirectory, CheckOutputFolder, CheckOutputFile

namespace uwbsar::slam {
struct MapOutputs;
struct MapRun;
}  // namespace uwbsar::slam

namespace uwbsar::tools {

/// Exit codes, documented in `uwbsar --help`.
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,   ///< an internal or I/O failure
  kExitUsage = 2,     ///< bad command line
  kExitBadInput = 3,  ///< bad input file or configuration (message names it)
};

struct GlobalOptions {
  /// --config, repeatable: merged in order, later wins; none = built-in defaults
  /// (config/default.yaml).
  std::vector<std::string> config_paths;
  bool quiet = false;
  bool verbose = false;
  /// The configuration, loaded once when the command line is parsed (before any subcommand
  /// runs), so a bad --config is refused by every subcommand before any work.
  std::shared_ptr<const AppConfig> config;
};

/// The configuration named by --config, or the defaults.
AppConfig LoadConfigFor(const GlobalOptions& globals);
/// Loads --config into globals->config; throws ConfigError (exit 3) for a bad file.
void LoadGlobalConfig(GlobalOptions* globals);

/// CLI11 checks of an input path: one that does not exist (or, for InputFile, a folder)
/// throws InputError, exit 3 like every other bad input file (CLI11's own checks are
/// command-line errors, exit 2). Other kinds of path are left to the loaders.
CLI::Validator InputFile();
CLI::Validator InputPath();
/// CLI11 check of an output path given as `option`: an empty one is refused with one line,
/// "--out: empty path" (exit 3).
CLI::Validator OutputPath(const std::string& option);

/// An output of a command: its option and path ("" when it was not given).
struct CommandOutput {
  std::string option;
  std::string path;
};

/// Refuses (InputError, naming both) an output that is or lies inside something the command
/// reads (slam::RefuseOutputOnInput): each of `outputs` against `inputs` and every --config
/// file. Every command that writes calls it first, before it creates or locks anything.
void RefuseOutputsOnInputs(const GlobalOptions& globals, const std::vector<CommandOutput>& outputs,
                           std::vector<slam::CommandInput> inputs);
/// A saved session named by a folder or its session file, as an input: its folder (the path
/// itself when there is nothing there), which may hold the output's folder. A session that is
/// joined (`map --resume`, `merge`) is not one: its folder may be the output by design.
slam::CommandInput SessionInput(const std::string& what, const std::string& dir_or_file);

/// CLI11 check functions ("" when valid). --seed: a decimal integer in [0, 2^64 - 1]
/// (CLI11 itself wraps -1 and saturates 2^64).
std::string CheckSeed(const std::string& text);
/// A finite number > 0 (CLI::PositiveNumber lets nan through).
std::string CheckPositiveFinite(const std::string& text);

/// "wrote FILE" for each of `files`, unless -q: on stdout, or on stderr when stdout carries a
/// JSON document (--json). Every command lists what it wrote.
void PrintWritten(const std::vector<std::string>& files, const GlobalOptions& globals,
                  bool json = false);

/// One line "wrote DIR: a, b, ..." (the names of `files`, paths in DIR), unless -q: the
/// outputs of a command that fills a folder.
/// "odometry calibration: ..." on stdout (not with -q): the base calibration the run applied
/// (backend.calibration_*_mean, `uwbsar calibrate`), or that there is none: map, demo and run
/// with their summary (a refusal stays one line).
void PrintOdometryCalibration(const Config& config, const GlobalOptions& globals);
void PrintWrittenFolder(const std::string& dir, const std::vector<std::string>& files,
                        const GlobalOptions& globals);

/// The five-line summary printed by `uwbsar map`, `uwbsar demo` and `uwbsar run`.
void PrintMapSummary(const slam::MapRun& run, const slam::MapOutputs& outputs,
                     const std::string& out_dir, const GlobalOptions& globals);

void AddConfigCommand(CLI::App& app, const GlobalOptions& globals);
void AddImageCommand(CLI::App& app, const GlobalOptions& globals);
void AddDemoCommand(CLI::App& app, const GlobalOptions& globals);
void AddOptimizeCommand(CLI::App& app, const GlobalOptions& globals);
void AddLoopsCommand(CLI::App& app, const GlobalOptions& globals);
void AddMatchCommand(CLI::App& app, const GlobalOptions& globals);
void AddDetectorsCommand(CLI::App& app, const GlobalOptions& globals);
void AddMapCommand(CLI::App& app, const GlobalOptions& globals);
void AddInfoCommand(CLI::App& app, const GlobalOptions& globals);
void AddCalibrateCommand(CLI::App& app, const GlobalOptions& globals);
void AddSimulateCommand(CLI::App& app, const GlobalOptions& globals);
void AddCompareCommand(CLI::App& app, const GlobalOptions& globals);
void AddExportPcdCommand(CLI::App& app, const GlobalOptions& globals);
void AddRunCommand(CLI::App& app, const GlobalOptions& globals);
void AddMergeCommand(CLI::App& app, const GlobalOptions& globals);
void AddLocalizeCommand(CLI::App& app, const GlobalOptions& globals);
void AddCheckCommand(CLI::App& app, const GlobalOptions& globals);

}  // namespace uwbsar::tools
