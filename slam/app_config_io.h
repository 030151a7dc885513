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

/// Same as LoadConfig, from YAML text; `source_name` is used in messages.
Config LoadConfigFromString(const std::string& yaml_text, const std::string& source_name);

/// Semantic checks of every section (positive sizes, known modes, sane ranges). Throws
/// ConfigError naming the key.
void ValidateConfig(const Config& config, const std::string& source_name);

/// Reads a point-target file for the simulator: a YAML mapping whose only key,
/// `point_targets`, lists {x_m, y_m, rcs_m2} entries as simulator.radar.point_targets does.
std::vector<PointTargetConfig> LoadPointTargets(const std::string& path);

}  // namespace uwbsar
