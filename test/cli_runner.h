// Runs the `uwbsar` binary (UWBSAR_BIN, set by the test's CMake target) or any
// command line as a user would, for the CLI tests.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace uwbsar::testing {

struct CliRun {
  int exit_code = -1;  ///< -1 when the command could not run or was killed
  std::string output;  ///< stdout, and stderr unless it was discarded
};

inline CliRun RunCommand(const std::string& command_line, bool merge_stderr = true) {
  CliRun run;
  FILE* pipe = popen((command_line + (merge_stderr ? " 2>&1" : " 2>/dev/null")).c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), pipe) != nullptr) run.output += buf.data();
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

#ifdef UWBSAR_BIN
/// `uwbsar <args>`.
inline CliRun Uwbsar(const std::string& args, bool merge_stderr = true) {
  return RunCommand(std::string(UWBSAR_BIN) + " " + args, merge_stderr);
}
#endif

}  // namespace uwbsar::testing
