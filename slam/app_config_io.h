// Loading the whole configuration file (slam/app_config.h) with the generic reader of
// core/config_io.h, and checking every section with the Validate() beside its Visit().
#pragma once

#include <string>
#include <vector>

#include "core/config_io.h"
#include "slam/app_config.h"

namespace uwbsar {

/// Loads a YAML file over the defaults: keys that are absent keep their default.
/// Throws ConfigError on unreadable files, unknown keys, wrong types or invalid values.
Config LoadConfig(const std::string& path);

/// Loads the files in order, each over the result of the ones before (the defaults for the
/// first): a key of a later file replaces the earlier value, a list as a whole (a robot's
/// configuration, then a calibration file from `uwbsar calibrate`). Each file is read and
/// checked for syntax, unknown keys and types; the merged result is validated once: a refused
/// value names the file and line that set it last ("b.yaml:4: 'slam.x' must be > 0"), one no
/// file set names the files ("a.yaml + b.yaml"). No files: the defaults.
Config LoadConfigs(const std::vector<std::string>& paths);

/// The configuration as a --config file that loads back to it (`uwbsar config`): every field,
/// and, since a file's radars merge by name into the defaults, `{name: N, remove: true}` for
/// each default radar it lacks. Radars kept in another order than the defaults' load back in
/// the defaults' order.
std::string ConfigFileYaml(const Config& config);

/// Same as LoadConfig, from YAML text; `source_name` is used in messages.
Config LoadConfigFromString(const std::string& yaml_text, const std::string& source_name);

/// Semantic checks of every section (positive sizes, known modes, sane ranges). Throws
/// ConfigError naming the key.
void ValidateConfig(const Config& config, const std::string& source_name);

/// Reads a point-target file for the simulator: a YAML mapping whose only key,
/// `point_targets`, lists {x_m, y_m, rcs_m2} entries as simulator.radar.point_targets does.
std::vector<PointTargetConfig> LoadPointTargets(const std::string& path);

}  // namespace uwbsar
