// The rule every configuration check uses: Validate() beside each section's Visit()
// (slam/config/system_config.h and the sections owned by higher folders) throws through it, so
// every message reads "<file>: '<dotted key>' <rule>", and the loader can put the line that set
// the key in front (slam/app_config_io.cc).
#pragma once

#include <string>
#include <utility>

#include "core/config_io.h"

namespace uwbsar {

/// A value a rule refuses: "<source>: '<key>' <rule>", with the key and the rule kept apart.
class ConfigValueError : public ConfigError {
 public:
  ConfigValueError(const std::string& source, std::string key, std::string rule)
      : ConfigError(source + ": '" + key + "' " + rule),
        key_(std::move(key)),
        rule_(std::move(rule)) {}
  const std::string& key() const { return key_; }
  const std::string& rule() const { return rule_; }

 private:
  std::string key_;
  std::string rule_;
};

namespace config_validation {

/// Throws ConfigValueError "<source>: '<key>' <rule>" unless `ok`.
inline void Require(bool ok, const std::string& source, const std::string& key,
                    const std::string& rule) {
  if (!ok) throw ConfigValueError(source, key, rule);
}

}  // namespace config_validation
}  // namespace uwbsar
