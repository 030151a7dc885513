#include "slam/config/config_fingerprint.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <map>
#include <sstream>

#include "core/config_io.h"

namespace uwbsar {
namespace {

/// Settings inside the sections below that do not change tiles or features.
bool Irrelevant(const std::string& key) {
  return key == "imaging.num_threads" || key == "enhance.colormap";
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

}  // namespace

std::vector<std::pair<std::string, std::string>> CompatibilityKeys(const SystemConfig& config) {
  const YAML::Node root = YAML::Load(ConfigToYaml(config));
  std::vector<std::pair<std::string, std::string>> out;
  for (const char* section : {"pulse", "radars", "imaging", "keyframe", "enhance"}) {
    Flatten(root[section], section, &out);
  }
  Flatten(root["place_recognition"]["detectors"], "place_recognition.detectors", &out);
  Flatten(root["slam"]["map_resolution_m"], "slam.map_resolution_m", &out);
  // imaging.ffbp.* shape tiles only when imaging.method is ffbp.
  if (config.imaging.method != ImagingMethod::kFfbp) {
    out.erase(
        std::remove_if(out.begin(), out.end(),
                       [](const auto& kv) { return kv.first.rfind("imaging.ffbp.", 0) == 0; }),
        out.end());
  }
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
    saved[line.substr(0, colon)] = line.substr(colon + 2);
  }
  // A setting added after a session was saved is not in it: that session was made as the
  // setting's built-in default makes tiles (e.g. imaging.method, direct, before ffbp existed).
  std::map<std::string, std::string> defaults;
  for (const auto& [key, value] : CompatibilityKeys(SystemConfig{})) defaults[key] = value;
  for (const auto& [key, value] : CompatibilityKeys(config)) {
    auto it = saved.find(key);
    if (it == saved.end()) {
      auto d = defaults.find(key);
      if (d != defaults.end() && d->second == value) continue;
      return key + " is not in the session (set to " + value + " here)";
    }
    if (it->second != value) {
      return key + " is " + it->second + " in the session, " + value + " in this configuration";
    }
    saved.erase(it);
  }
  if (!saved.empty())
    return saved.begin()->first + " is in the session but not in this configuration";
  return "";
}

}  // namespace uwbsar
