// What `uwbsar` prints when a command fails: one line "uwbsar: error: <what>" and its exit code
// (tools/commands.h). A command-line error names what the user typed wrong first (an unknown
// option or subcommand, with the closest known one) and points to the command's own --help.
#pragma once

#include <CLI/CLI.hpp>

namespace uwbsar::tools {

/// For main()'s catch (...): prints the exception being handled as one line and returns the
/// exit code (CLI11's --help and --version print their text, exit 0). Must be called while an
/// exception is handled; `app` is the parsed (or half-parsed) command line.
int ReportError(const CLI::App& app, int argc, char** argv);

}  // namespace uwbsar::tools
