#include <filesystem>

#include "slam/config_io.h"
#include "tools/commands.h"

namespace uwbsar::tools {

Config LoadConfigFor(const GlobalOptions& globals) {
  if (globals.config_path.empty()) return Config{};
  return LoadConfig(globals.config_path);
}

void EnsureDirectory(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw InputError(dir + ": cannot create output folder: " + ec.message());
  }
}

void AddConfigCommand(CLI::App& app, const GlobalOptions& globals) {
  CLI::App* cmd = app.add_subcommand("config", "Print the effective configuration as YAML");
  cmd->callback([&globals] { std::cout << ConfigToYaml(LoadConfigFor(globals)) << "\n"; });
}

}  // namespace uwbsar::tools
