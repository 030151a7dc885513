#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "app/app_config_io.h"
#include "core/errors.h"
#include "slam/session/session_file.h"
#include "tools/commands.h"

namespace uwbsar::tools {

AppConfig LoadConfigFor(const GlobalOptions& globals) {
  if (globals.config) return *globals.config;
  return LoadConfigs(globals.config_paths);
}

void LoadGlobalConfig(GlobalOptions* globals) {
  if (globals->config_paths.empty()) return;
  globals->config = std::make_shared<const AppConfig>(LoadConfigs(globals->config_paths));
}

namespace {

CLI::Validator InputCheck(bool file) {
  return CLI::Validator(
      [file](std::string& path) {
        std::error_code ec;
        const std::filesystem::file_status st = std::filesystem::status(path, ec);
        if (!std::filesystem::exists(st)) throw InputError(path + ": no such file or folder");
        if (file && std::filesystem::is_directory(st)) {
          throw InputError(path + ": is a folder, expected a file");
        }
        return std::string();
      },
      file ? "FILE" : "PATH");
}

}  // namespace

CLI::Validator InputFile() { return InputCheck(true); }
CLI::Validator InputPath() { return InputCheck(false); }

CLI::Validator OutputPath(const std::string& option) {
  return CLI::Validator(
      [option](std::string& path) {
        if (path.empty()) throw InputError(option + ": empty path");
        return std::string();
      },
      "PATH");
}

void RefuseOutputsOnInputs(const GlobalOptions& globals, const std::vector<CommandOutput>& outputs,
                           std::vector<slam::CommandInput> inputs) {
  for (const std::string& config : globals.config_paths) {
    inputs.push_back({"the --config file", config});
  }
  for (const CommandOutput& out : outputs) slam::RefuseOutputOnInput(out.option, out.path, inputs);
}

slam::CommandInput SessionInput(const std::string& what, const std::string& dir_or_file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::string folder = dir_or_file;
  if (fs::is_regular_file(dir_or_file, ec)) {
    folder = fs::path(dir_or_file).parent_path().string();
    if (folder.empty()) folder = ".";
  }
  return {what, folder, /*may_hold_output=*/true};
}

std::string CheckSeed(const std::string& text) {
  const std::string error =
      "expected an integer from 0 to 18446744073709551615, got '" + text + "'";
  if (text.empty() || text.size() > 20 ||
      text.find_first_not_of("0123456789") != std::string::npos) {
    return error;
  }
  errno = 0;
  std::strtoull(text.c_str(), nullptr, 10);
  return errno == ERANGE ? error : std::string();
}

std::string CheckPositiveFinite(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v) || !(v > 0)) {
    return "expected a finite number > 0, got '" + text + "'";
  }
  return {};
}

void PrintWritten(const std::vector<std::string>& files, const GlobalOptions& globals, bool json) {
  if (globals.quiet) return;
  for (const std::string& f : files) std::fprintf(json ? stderr : stdout, "wrote %s\n", f.c_str());
}

void PrintWrittenFolder(const std::string& dir, const std::vector<std::string>& files,
                        const GlobalOptions& globals) {
  if (globals.quiet || files.empty()) return;
  std::string names;
  for (const std::string& f : files) {
    names += (names.empty() ? "" : ", ") + std::filesystem::path(f).filename().string();
  }
  std::printf("wrote %s: %s\n", dir.c_str(), names.c_str());
}

void PrintOdometryCalibration(const Config& config, const GlobalOptions& globals) {
  if (globals.quiet) return;
  const BackendConfig& b = config.backend;
  if (b.calibration_scale_mean == 0.0 && b.calibration_heading_drift_mean_rad_per_m == 0.0 &&
      b.calibration_rotation_mean == 0.0) {
    std::printf(
        "odometry calibration: none (the base's measured one, from `uwbsar calibrate` on a run "
        "with ground truth, is given with --config)\n");
    return;
  }
  std::printf(
      "odometry calibration: distance scale %+.3f %%, heading drift %+.5f rad/m, rotation scale "
      "%+.3f %% (backend.calibration_*_mean)%s\n",
      100.0 * b.calibration_scale_mean, b.calibration_heading_drift_mean_rad_per_m,
      100.0 * b.calibration_rotation_mean,
      b.odometry_calibration ? ", refined while loops constrain it" : "");
}

void AddConfigCommand(CLI::App& app, const GlobalOptions& globals) {
  CLI::App* cmd = app.add_subcommand("config", "Print the effective configuration as YAML");
  cmd->callback([&globals] { std::cout << ConfigFileYaml(LoadConfigFor(globals)) << "\n"; });
}

}  // namespace uwbsar::tools
