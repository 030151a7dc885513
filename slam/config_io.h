// YAML <-> configuration structs. Any struct with a Visit(V&) listing its
// fields can be read and written; unknown keys and wrong types are errors that
// name the file, the line and the dotted key. YAML is parsed here and nowhere
// else in the core.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "slam/config.h"
#include "slam/errors.h"

namespace uwbsar {

/// Bad configuration input (file, key, value). what() is a complete one-line message.
class ConfigError : public InputError {
 public:
  using InputError::InputError;
};

/// Loads a YAML file over the defaults: keys that are absent keep their default.
/// Throws ConfigError on unreadable files, unknown keys, wrong types or invalid values.
Config LoadConfig(const std::string& path);

/// Same as LoadConfig, from YAML text; `source_name` is used in messages.
Config LoadConfigFromString(const std::string& yaml_text, const std::string& source_name);

/// Semantic checks (positive sizes, known modes, sane ranges). Throws ConfigError naming the key.
void ValidateConfig(const Config& config, const std::string& source_name);

/// Reads a point-target file for the simulator: a YAML mapping whose only key,
/// `point_targets`, lists {x_m, y_m, rcs_m2} entries as simulator.radar.point_targets does.
std::vector<PointTargetConfig> LoadPointTargets(const std::string& path);

/// The configuration as YAML (every field, no comments), e.g. for run summaries.
std::string ConfigToYaml(const Config& config);

}  // namespace uwbsar
