#include "app/app_config_io.h"

#include <algorithm>

#include "core/config_require.h"

namespace uwbsar {
namespace {

/// ValidateConfig, its refusal of a value that a file set naming the file and line that set it
/// last (a key left at its default, or refused with another, keeps naming the files).
void ValidateLoaded(const AppConfig& config, const std::string& sources,
                    const ConfigOrigins& origins) {
  try {
    ValidateConfig(config, sources);
  } catch (const ConfigValueError& e) {
    const auto origin = origins.find(e.key());
    if (origin == origins.end()) throw;
    throw ConfigError(origin->second + ": '" + e.key() + "' " + e.rule());
  }
}

}  // namespace

void ValidateConfig(const AppConfig& c, const std::string& src) {
  Validate(c.compare, src);
  ValidateConfig(static_cast<const Config&>(c), src);
}

AppConfig LoadConfigFromString(const std::string& yaml_text, const std::string& source_name) {
  ConfigOrigins origins;
  AppConfig config = ReadConfigYaml<AppConfig>(yaml_text, source_name, &origins);
  ValidateLoaded(config, source_name, origins);
  return config;
}

AppConfig LoadConfig(const std::string& path) {
  return LoadConfigFromString(ReadConfigText(path, "configuration"), path);
}

AppConfig LoadConfigs(const std::vector<std::string>& paths) {
  if (paths.size() == 1) return LoadConfig(paths.front());
  AppConfig config;
  ConfigOrigins origins;
  for (const std::string& path : paths) {
    config = ReadConfigYamlOver(ReadConfigText(path, "configuration"), path, std::move(config),
                                &origins);
  }
  // Checked merged: a calibration file alone need not be a whole valid configuration.
  std::string sources;
  for (const std::string& path : paths) sources += (sources.empty() ? "" : " + ") + path;
  if (!paths.empty()) ValidateLoaded(config, sources, origins);
  return config;
}

std::string ConfigFileYaml(const AppConfig& config) {
  const std::string yaml = ConfigToYaml(config);
  YAML::Node root;
  bool removes = false;
  for (const RadarConfig& d : DefaultRadars()) {
    const bool kept = std::any_of(config.radars.begin(), config.radars.end(),
                                  [&d](const RadarConfig& r) { return r.name == d.name; });
    if (kept) continue;
    if (!removes) root = YAML::Load(yaml);
    removes = true;
    YAML::Node removed;
    removed["name"] = d.name;
    removed["remove"] = true;
    root["radars"].push_back(removed);
  }
  if (!removes) return yaml;  // the usual case, unchanged
  YAML::Emitter out;
  out << root;
  return out.c_str();
}

}  // namespace uwbsar
