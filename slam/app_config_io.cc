#include "slam/app_config_io.h"

#include <algorithm>

#include "core/bounded_file.h"
#include "core/config_require.h"

namespace uwbsar {
namespace {

/// A point-target file: `point_targets:` followed by the same entries as the configuration.
struct PointTargetFile {
  std::vector<PointTargetConfig> point_targets;

  template <class V>
  void Visit(V& v) {
    v("point_targets", point_targets);
  }
};

}  // namespace

void ValidateConfig(const Config& c, const std::string& src) {
  Validate(c.live, src);
  Validate(c.dds, src);
  Validate(c.simulator, src);
  Validate(c.session, src);
  ValidateSystemConfig(c, src);
}

std::string ReadConfigText(const std::string& path, const char* what) {
  try {
    return ReadBoundedFile(path, what);
  } catch (const InputError& e) {
    throw ConfigError(e.what());
  }
}

std::vector<PointTargetConfig> LoadPointTargets(const std::string& path) {
  const std::string text = ReadConfigText(path, "point-target");
  YAML::Node root;
  try {
    root = ParseYamlDocument(text, path);
  } catch (const InputError& e) {
    throw ConfigError(e.what());
  }
  if (!root.IsMap()) throw ConfigError(path + ": expected a mapping with 'point_targets'");
  PointTargetFile file;
  config_yaml::Reader reader(root, path, "");
  file.Visit(reader);
  reader.CheckUnknownKeys();
  for (std::size_t i = 0; i < file.point_targets.size(); ++i) {
    if (!(file.point_targets[i].rcs_m2 >= 0)) {
      throw ConfigError(path + ": 'point_targets[" + std::to_string(i) + "].rcs_m2' must be >= 0");
    }
  }
  return file.point_targets;
}

}  // namespace uwbsar
