// Checking the SLAM library's sections of the configuration (slam/app_config.h) with the
// Validate() beside each section's Visit(), and the simulator's point-target files. The whole
// file is loaded above, by app/app_config_io.h.
#pragma once

#include <string>
#include <vector>

#include "core/config_io.h"
#include "slam/app_config.h"

namespace uwbsar {

/// The text of a configuration file (at most limits' default size); ConfigError naming the
/// file when it cannot be read. `what` names the kind of file in the message.
std::string ReadConfigText(const std::string& path, const char* what);

/// Semantic checks of every section of Config (positive sizes, known modes, sane ranges).
/// Throws ConfigError naming the key.
void ValidateConfig(const Config& config, const std::string& source_name);

/// Reads a point-target file for the simulator: a YAML mapping whose only key,
/// `point_targets`, lists {x_m, y_m, rcs_m2} entries as simulator.radar.point_targets does.
std::vector<PointTargetConfig> LoadPointTargets(const std::string& path);

}  // namespace uwbsar
