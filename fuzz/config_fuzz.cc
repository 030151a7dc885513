// libFuzzer target: the configuration loader (YAML -> Config, unknown keys, types, shapes,
// validation) on arbitrary text. Contract under test: bad input throws ConfigError naming
// the source; no other exception escapes (a raw yaml-cpp exception would exit 1, not 3) and
// nothing crashes; an accepted configuration prints and loads back.
#include <cstddef>
#include <cstdint>
#include <string>

#include "app/app_config_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const uwbsar::AppConfig config = uwbsar::LoadConfigFromString(text, "fuzz.yaml");
    uwbsar::LoadConfigFromString(uwbsar::ConfigFileYaml(config), "round-trip");
  } catch (const uwbsar::ConfigError& e) {
    const std::string what = e.what();
    if (what.rfind("fuzz.yaml", 0) != 0) __builtin_trap();  // names the file
  }
  return 0;
}
