// Runs the `uwbsar` binary (UWBSAR_BIN, set by the test's CMake target) or any
// command line as a user would, for the CLI tests.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
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

/// A fresh folder `<tmp>/<prefix>_<name>_<pid>`: one per process, as ctest runs the tests of
/// a suite in parallel processes.
inline std::string FreshFolder(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    (prefix + "_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline void WriteTextFile(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

/// The number of lines of `text` (a message is one line).
inline int LineCount(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

/// A tiny text log (`uwbsar image --log`): the robot drives 0.3 m while the left radar, with
/// `samples` samples a scan, sees one echo at sample 200.
inline std::string TinyTextLog(int samples) {
  std::string log;
  for (int i = 0; i <= 30; ++i) {
    log += "odom " + std::to_string(1000000000LL + i * 20000000LL) + " " +
           std::to_string(i * 0.01) + " 0 0\n";
  }
  for (int i = 0; i < 25; ++i) {
    log +=
        "scan " + std::to_string(1010000000LL + i * 20000000LL) + " 0 " + std::to_string(samples);
    for (int k = 0; k < samples; ++k) log += (k == 200 ? " 1.0" : " 0");
    log += "\n";
  }
  return log;
}

#ifdef UWBSAR_BIN
/// `uwbsar <args>`.
inline CliRun Uwbsar(const std::string& args, bool merge_stderr = true) {
  return RunCommand(std::string(UWBSAR_BIN) + " " + args, merge_stderr);
}
#endif

}  // namespace uwbsar::testing
