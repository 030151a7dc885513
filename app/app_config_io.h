// Loading the whole configuration file (app/app_config.h) with the generic reader of
// core/config_io.h, and checking every section with the Validate() beside its Visit().
#pragma once

#include <string>
#include <vector>

#include "app/app_config.h"
#include "slam/app_config_io.h"

namespace uwbsar {

/// Loads a YAML file over the defaults: keys that are absent keep their default.
/// Throws ConfigError on unreadable files, unknown keys, wrong types or invalid values.
AppConfig LoadConfig(const std::string& path);

/// Loads the files in order, each over the result of the ones before (the defaults for the
/// first): a key of a later file replaces the earlier value, a list as a whole (a robot's
/// configuration, then a calibration file from `uwbsar calibrate`). Each file is read and
/// checked for syntax, unknown keys and types; the merged result is validated once: a refused
/// value names the file and line that set it last ("b.yaml:4: 'slam.x' must be > 0"), one no
/// file set names the files ("a.yaml + b.yaml"). No files: the defaults.
AppConfig LoadConfigs(const std::vector<std::string>& paths);

/// The configuration as a --config file that loads back to it (`uwbsar config`): every field,
/// and, since a file's radars merge by name into the defaults, `{name: N, remove: true}` for
/// each default radar it lacks. Radars kept in another order than the defaults' load back in
/// the defaults' order.
std::string ConfigFileYaml(const AppConfig& config);

/// Same as LoadConfig, from YAML text; `source_name` is used in messages.
AppConfig LoadConfigFromString(const std::string& yaml_text, const std::string& source_name);

/// Semantic checks of every section of the file: the evaluation's, then Config's
/// (slam/app_config_io.h). Throws ConfigError naming the key.
void ValidateConfig(const AppConfig& config, const std::string& source_name);

}  // namespace uwbsar
