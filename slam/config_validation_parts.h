// The parts of ValidateConfig (slam/config_io.h) that live in their own files, and the
// rule they all use. Internal to slam/config_validation*.cc.
#pragma once

#include <string>

#include "slam/config.h"
#include "slam/config_io.h"

namespace uwbsar::config_validation {

/// Throws ConfigError "<source>: '<key>' <rule>" unless `ok`.
inline void Require(bool ok, const std::string& source, const std::string& key,
                    const std::string& rule) {
  if (!ok) throw ConfigError(source + ": '" + key + "' " + rule);
}

/// dds.* (slam/config_validation_live.cc).
void ValidateDds(const DdsConfig& d, const std::string& src);
/// live.* (slam/config_validation_live.cc).
void ValidateLive(const LiveConfig& l, const std::string& src);
/// The sizes the imaging and map settings imply against limits.*
/// (slam/config_limits_validation.cc).
void ValidateLimits(const Config& c, const std::string& src);

}  // namespace uwbsar::config_validation
