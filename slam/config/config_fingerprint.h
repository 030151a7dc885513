// The settings a saved session depends on: imaging geometry and feature
// settings. A session's keyframe tiles and features are only comparable with new ones
// made with the same values, so a session records them and refuses to be read under a
// configuration that differs in any of them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "slam/config/system_config.h"

namespace uwbsar {

/// (dotted key, value as YAML scalar text) of every compatibility-relevant setting, in a
/// fixed order: pulse.*, radars[*].*, imaging.* (not num_threads, method or ffbp.*), keyframe.*,
/// enhance.*
/// (not colormap), place_recognition.detectors.*, slam.map_resolution_m.
std::vector<std::pair<std::string, std::string>> CompatibilityKeys(const SystemConfig& config);

/// CompatibilityKeys as text, one `key: value` line each (what a session stores).
std::string ConfigFingerprint(const SystemConfig& config);

/// Empty when `stored` (a ConfigFingerprint text) matches `config`; otherwise one line
/// naming the first key that differs, e.g. "imaging.pixel_size_m is 0.01 in the session,
/// 0.005 in this configuration".
std::string FingerprintDifference(const std::string& stored, const SystemConfig& config);

}  // namespace uwbsar
