#include "imaging/sar_grid_metadata.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <utility>

#include "core/errors.h"
#include "core/pose2.h"
#include "core/yaml_file.h"

namespace uwbsar {
namespace {

template <class T>
T Require(const std::string& file, const YAML::Node& root, const char* key) {
  const YAML::Node node = root[key];
  if (!node) throw InputError(file + ": missing grid key '" + key + "'");
  return YamlValue<T>(file, node, key, "grid");
}

}  // namespace

SarGridMetadata LoadSarGridMetadata(const std::string& yaml_path) {
  const YAML::Node root = LoadYamlMappingFile(yaml_path, "grid");
  SarGridMetadata g;
  g.x0_m = Require<double>(yaml_path, root, "x0_m");
  g.y0_m = Require<double>(yaml_path, root, "y0_m");
  g.resolution_m = Require<double>(yaml_path, root, "resolution_m");
  const bool has_size = root["rows"] || root["cols"];
  if (has_size) {
    g.rows = Require<int>(yaml_path, root, "rows");
    g.cols = Require<int>(yaml_path, root, "cols");
  }
  if (root["mode"]) g.mode = Require<std::string>(yaml_path, root, "mode");
  if (root["image"]) {
    const std::filesystem::path image = Require<std::string>(yaml_path, root, "image");
    if (image.empty())
      throw InputError(YamlWhere(yaml_path, root["image"]) + ": grid key 'image' is empty");
    g.image = image.is_absolute()
                  ? image.string()
                  : (std::filesystem::path(yaml_path).parent_path() / image).string();
  }
  if (!std::isfinite(g.x0_m) || !std::isfinite(g.y0_m)) {
    throw InputError(yaml_path + ": grid keys 'x0_m' and 'y0_m' must be finite");
  }
  const std::pair<const char*, double> corner[] = {{"x0_m", g.x0_m}, {"y0_m", g.y0_m}};
  for (const auto& [key, v] : corner) {
    if (std::abs(v) <= kMaxWorldCoordinateM) continue;
    std::ostringstream what;
    what << YamlWhere(yaml_path, root[key]) << ": grid key '" << key << "' is " << v
         << " m, beyond " << kMaxWorldCoordinateM << " m";
    throw InputError(what.str());
  }
  if (!(g.resolution_m > 0.0) || !std::isfinite(g.resolution_m)) {
    throw InputError(YamlWhere(yaml_path, root["resolution_m"]) +
                     ": grid key 'resolution_m' must be > 0");
  }
  if (g.resolution_m < kMinGridResolutionM || g.resolution_m > kMaxGridResolutionM) {
    std::ostringstream msg;
    msg << YamlWhere(yaml_path, root["resolution_m"]) << ": grid key 'resolution_m' is "
        << g.resolution_m << " m per pixel, outside [" << kMinGridResolutionM << ", "
        << kMaxGridResolutionM << "] (a SAR image's pixel is millimetres to centimetres)";
    throw InputError(msg.str());
  }
  if (has_size && (g.rows < 1 || g.cols < 1)) {
    throw InputError(yaml_path + ": grid keys 'rows' and 'cols' must be >= 1");
  }
  return g;
}

}  // namespace uwbsar
