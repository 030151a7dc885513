#include "slam/config/config_fingerprint.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <sstream>

#include "core/config_io.h"

namespace uwbsar {
namespace {

/// Settings inside the sections below that do not change tiles or features enough to matter.
/// imaging.method and imaging.ffbp.*: ffbp's tiles are direct's to the interpolation error of
/// its polar grids (NCC >= 0.99 of the detected tiles, BM_ImageTile and FfbpTest), so a session
/// made with either is resumed, localised in or merged under the other: switching methods (for
/// speed, or back) loses no saved map.
bool Irrelevant(const std::string& key) {
  return key == "imaging.num_threads" || key == "enhance.colormap" || key == "imaging.method" ||
         key.rfind("imaging.ffbp.", 0) == 0;
}

void Flatten(const YAML::Node& node, const std::string& prefix,
             std::vector<std::pair<std::string, std::string>>* out) {
  if (node.IsMap()) {
    for (const auto& item : node) {
      Flatten(item.second, prefix + "." + item.first.as<std::string>(), out);
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      Flatten(node[i], prefix + "[" + std::to_string(i) + "]", out);
    }
  } else if (!Irrelevant(prefix)) {
    out->push_back({prefix, node.IsNull() ? std::string() : node.Scalar()});
  }
}

/// The same text, or the same number however it is written: sessions saved before numbers
/// were written shortest hold "0.0050000000000000001" where this one writes "0.005".
bool SameValue(const std::string& a, const std::string& b) {
  if (a == b) return true;
  char* end_a = nullptr;
  char* end_b = nullptr;
  const double x = std::strtod(a.c_str(), &end_a);
  const double y = std::strtod(b.c_str(), &end_b);
  return !a.empty() && !b.empty() && *end_a == '\0' && *end_b == '\0' && x == y;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> CompatibilityKeys(const SystemConfig& config) {
  const YAML::Node root = YAML::Load(ConfigToYaml(config));
  std::vector<std::pair<std::string, std::string>> out;
  for (const char* section : {"pulse", "radars", "imaging", "keyframe", "enhance"}) {
    Flatten(root[section], section, &out);
  }
  Flatten(root["place_recognition"]["detectors"], "place_recognition.detectors", &out);
  Flatten(root["slam"]["map_resolution_m"], "slam.map_resolution_m", &out);
  return out;
}

std::string ConfigFingerprint(const SystemConfig& config) {
  std::ostringstream text;
  for (const auto& [key, value] : CompatibilityKeys(config)) text << key << ": " << value << "\n";
  return text.str();
}

std::string FingerprintDifference(const std::string& stored, const SystemConfig& config) {
  std::map<std::string, std::string> saved;
  std::istringstream in(stored);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos) {
      if (!line.empty() && line.back() == ':') saved[line.substr(0, line.size() - 1)] = "";
      continue;
    }
    if (!Irrelevant(line.substr(0, colon))) saved[line.substr(0, colon)] = line.substr(colon + 2);
  }
  // A setting added after a session was saved is not in it: that session was made as the
  // setting's built-in default makes tiles.
  std::map<std::string, std::string> defaults;
  for (const auto& [key, value] : CompatibilityKeys(SystemConfig{})) defaults[key] = value;
  for (const auto& [key, value] : CompatibilityKeys(config)) {
    auto it = saved.find(key);
    if (it == saved.end()) {
      auto d = defaults.find(key);
      if (d != defaults.end() && SameValue(d->second, value)) continue;
      return key + " is not in the session (set to " + value + " here)";
    }
    if (!SameValue(it->second, value)) {
      return key + " is " + it->second + " in the session, " + value + " in this configuration";
    }
    saved.erase(it);
  }
  if (!saved.empty())
    return saved.begin()->first + " is in the session but not in this configuration";
  return "";
}

}  // namespace uwbsar
