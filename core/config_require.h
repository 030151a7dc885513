// The rule every configuration check uses: Validate() beside each section's Visit()
// (slam/config/system_config.h and the sections owned by higher folders) throws through it, so
// every message reads "<file>: '<dotted key>' <rule>".
#pragma once

#include <string>

#include "core/config_io.h"

namespace uwbsar::config_validation {

/// Throws ConfigError "<source>: '<key>' <rule>" unless `ok`.
inline void Require(bool ok, const std::string& source, const std::string& key,
                    const std::string& rule) {
  if (!ok) throw ConfigError(source + ": '" + key + "' " + rule);
}

}  // namespace uwbsar::config_validation
