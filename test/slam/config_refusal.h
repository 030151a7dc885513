// The configuration tests' one-line refusals: what LoadConfigFromString says of a YAML text.
#pragma once

#include <string>

#include "app/app_config_io.h"

namespace uwbsar {

/// The ConfigError message LoadConfigFromString(yaml, file) refuses `yaml` with ("" if it loads).
inline std::string RefusalOf(const std::string& yaml, const std::string& file = "x.yaml") {
  try {
    LoadConfigFromString(yaml, file);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace uwbsar
