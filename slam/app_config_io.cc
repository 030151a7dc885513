#include "slam/app_config_io.h"

#include <algorithm>

#include "core/bounded_file.h"
#include "core/config_require.h"

namespace uwbsar {
namespace {

/// A point-target file: `point_targets:` followed by the same entries as the configuration.
struct PointTargetFile {
  std::vector<PointTargetConfig> point_targets;

  template <class V>
  void Visit(V& v) {
    v("point_targets", point_targets);
  }
};

std::string ReadConfigFile(const std::string& path, const char* what) {
  try {
    return ReadBoundedFile(path, what);
  } catch (const InputError& e) {
    throw ConfigError(e.what());
  }
}

/// ValidateConfig, its refusal of a value that a file set naming the file and line that set it
/// last (a key left at its default, or refused with another, keeps naming the files).
void ValidateLoaded(const Config& config, const std::string& sources,
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

void ValidateConfig(const Config& c, const std::string& src) {
  Validate(c.compare, src);
  Validate(c.live, src);
  Validate(c.dds, src);
  Validate(c.simulator, src);
  Validate(c.session, src);
  ValidateSystemConfig(c, src);
}

Config LoadConfigFromString(const std::string& yaml_text, const std::string& source_name) {
  ConfigOrigins origins;
  Config config = ReadConfigYaml<Config>(yaml_text, source_name, &origins);
  ValidateLoaded(config, source_name, origins);
  return config;
}

Config LoadConfig(const std::string& path) {
  return LoadConfigFromString(ReadConfigFile(path, "configuration"), path);
}

Config LoadConfigs(const std::vector<std::string>& paths) {
  if (paths.size() == 1) return LoadConfig(paths.front());
  Config config;
  ConfigOrigins origins;
  for (const std::string& path : paths) {
    config = ReadConfigYamlOver(ReadConfigFile(path, "configuration"), path, std::move(config),
                                &origins);
  }
  // Checked merged: a calibration file alone need not be a whole valid configuration.
  std::string sources;
  for (const std::string& path : paths) sources += (sources.empty() ? "" : " + ") + path;
  if (!paths.empty()) ValidateLoaded(config, sources, origins);
  return config;
}

std::string ConfigFileYaml(const Config& config) {
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

std::vector<PointTargetConfig> LoadPointTargets(const std::string& path) {
  const std::string text = ReadConfigFile(path, "point-target");
  YAML::Node root;
  try {
    root = ParseYamlDocument(text, path);
  } catch (const InputError& e) {
    throw ConfigError(e.what());
  }
  if (!root.IsMap()) throw ConfigError(path + ": expected a mapping with 'point_targets'");
  PointTargetFile file;
  config_yaml::Reader reader(root, path, "");
  file.Visit(reader);
  reader.CheckUnknownKeys();
  for (std::size_t i = 0; i < file.point_targets.size(); ++i) {
    if (!(file.point_targets[i].rcs_m2 >= 0)) {
      throw ConfigError(path + ": 'point_targets[" + std::to_string(i) + "].rcs_m2' must be >= 0");
    }
  }
  return file.point_targets;
}

}  // namespace uwbsar
