#include "slam/config_io.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <type_traits>

namespace uwbsar {
namespace {

template <class T, class = void>
struct HasVisit : std::false_type {};
template <class T>
struct HasVisit<T, std::void_t<decltype(std::declval<T&>().Visit(std::declval<int&>()))>>
    : std::true_type {};
// Visit is a template, so probing it with int& only checks that the member exists.

template <class T>
struct IsVector : std::false_type {};
template <class T>
struct IsVector<std::vector<T>> : std::true_type {};

std::string Where(const std::string& source, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  std::ostringstream out;
  out << source;
  if (mark.line >= 0) out << ":" << (mark.line + 1);
  return out.str();
}

/// Reads a YAML mapping into a struct, recording which keys it knows.
class Reader {
 public:
  Reader(const YAML::Node& node, std::string source, std::string prefix)
      : node_(node), source_(std::move(source)), prefix_(std::move(prefix)) {}

  template <class T>
  void operator()(const char* key, T& value) {
    known_.insert(key);
    const YAML::Node child = node_[key];
    if (child) Read(child, value, prefix_ + key);
  }

  /// Throws if the mapping holds a key that no field claimed.
  void CheckUnknownKeys() const {
    for (const auto& kv : node_) {
      const std::string key = kv.first.as<std::string>();
      if (!known_.count(key)) {
        throw ConfigError(Where(source_, kv.first) + ": unknown key '" + prefix_ + key + "'");
      }
    }
  }

  template <class T>
  void Read(const YAML::Node& node, T& value, const std::string& key) {
    if constexpr (HasVisit<T>::value) {
      if (!node.IsMap()) throw ConfigError(Where(source_, node) + ": '" + key + "' must be a mapping");
      Reader nested(node, source_, key + ".");
      value.Visit(nested);
      nested.CheckUnknownKeys();
    } else if constexpr (IsVector<T>::value) {
      if (!node.IsSequence()) {
        throw ConfigError(Where(source_, node) + ": '" + key + "' must be a list");
      }
      T items(node.size());
      for (std::size_t i = 0; i < node.size(); ++i) {
        Read(node[i], items[i], key + "[" + std::to_string(i) + "]");
      }
      value = std::move(items);
    } else {
      if (!node.IsScalar()) throw ConfigError(Where(source_, node) + ": '" + key + "' must be a value");
      try {
        value = node.as<T>();
      } catch (const YAML::Exception&) {
        throw ConfigError(Where(source_, node) + ": '" + key + "' has invalid value '" +
                          node.Scalar() + "'");
      }
      if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(value)) {
          throw ConfigError(Where(source_, node) + ": '" + key + "' must be finite");
        }
      }
    }
  }

 private:
  const YAML::Node& node_;
  std::string source_;
  std::string prefix_;
  std::set<std::string> known_;
};

/// Writes a struct as a YAML mapping.
class Writer {
 public:
  explicit Writer(YAML::Emitter& out) : out_(out) {}

  template <class T>
  void operator()(const char* key, T& value) {
    out_ << YAML::Key << key << YAML::Value;
    Write(value);
  }

  template <class T>
  void Write(T& value) {
    if constexpr (HasVisit<T>::value) {
      out_ << YAML::BeginMap;
      value.Visit(*this);
      out_ << YAML::EndMap;
    } else if constexpr (IsVector<T>::value) {
      out_ << YAML::BeginSeq;
      for (auto& item : value) Write(item);
      out_ << YAML::EndSeq;
    } else {
      out_ << value;
    }
  }

 private:
  YAML::Emitter& out_;
};

void Require(bool ok, const std::string& source, const std::string& key, const std::string& rule) {
  if (!ok) throw ConfigError(source + ": '" + key + "' " + rule);
}

}  // namespace

Config LoadConfigFromString(const std::string& yaml_text, const std::string& source_name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source_name + ":" + std::to_string(e.mark.line + 1) +
                      ": YAML syntax error: " + e.msg);
  }
  Config config;
  if (root.IsNull()) return config;  // an empty file means all defaults
  if (!root.IsMap()) throw ConfigError(source_name + ": the top level must be a mapping");
  Reader reader(root, source_name, "");
  config.Visit(reader);
  reader.CheckUnknownKeys();
  ValidateConfig(config, source_name);
  return config;
}

Config LoadConfig(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open configuration file");
  std::stringstream text;
  text << in.rdbuf();
  return LoadConfigFromString(text.str(), path);
}

void ValidateConfig(const Config& c, const std::string& src) {
  Require(c.pulse.center_frequency_hz > 0, src, "pulse.center_frequency_hz", "must be > 0");
  Require(c.pulse.bandwidth_hz > 0, src, "pulse.bandwidth_hz", "must be > 0");
  Require(c.pulse.sampling_frequency_hz > 2 * c.pulse.center_frequency_hz, src,
          "pulse.sampling_frequency_hz", "must exceed twice the centre frequency");
  Require(!c.radars.empty(), src, "radars", "must list at least one radar");
  for (std::size_t i = 0; i < c.radars.size(); ++i) {
    const RadarConfig& r = c.radars[i];
    const std::string k = "radars[" + std::to_string(i) + "].";
    Require(r.fov_half_angle_deg > 0 && r.fov_half_angle_deg <= 90, src, k + "fov_half_angle_deg",
            "must be in (0, 90]");
    Require(r.min_range_m >= 0, src, k + "min_range_m", "must be >= 0");
    Require(r.max_range_m > r.min_range_m, src, k + "max_range_m", "must exceed min_range_m");
    Require(r.num_samples > 1, src, k + "num_samples", "must be > 1");
    Require(r.zero_leading_samples >= 0 && r.zero_leading_samples < r.num_samples, src,
            k + "zero_leading_samples", "must be in [0, num_samples)");
  }
  Require(c.imaging.mode == "paper" || c.imaging.mode == "coherent", src, "imaging.mode",
          "must be 'paper' or 'coherent'");
  Require(c.imaging.pixel_size_m > 0, src, "imaging.pixel_size_m", "must be > 0");
  Require(c.imaging.coherent_oversampling >= 1 && c.imaging.coherent_oversampling <= 64, src,
          "imaging.coherent_oversampling", "must be in [1, 64]");
  Require(c.imaging.num_threads >= 0, src, "imaging.num_threads", "must be >= 0");
  Require(c.gating.min_travel_m >= 0, src, "gating.min_travel_m", "must be >= 0");
  Require(c.gating.max_odom_jump_m > 0, src, "gating.max_odom_jump_m", "must be > 0");
  Require(c.gating.max_odom_gap_s > 0, src, "gating.max_odom_gap_s", "must be > 0");
  Require(c.gating.max_scan_latency_s > 0, src, "gating.max_scan_latency_s", "must be > 0");
  Require(c.keyframe.tile_length_m > 0, src, "keyframe.tile_length_m", "must be > 0");
  Require(c.keyframe.tile_spacing_m > 0 && c.keyframe.tile_spacing_m <= c.keyframe.tile_length_m,
          src, "keyframe.tile_spacing_m", "must be in (0, tile_length_m]");
  Require(c.keyframe.margin_m >= 0, src, "keyframe.margin_m", "must be >= 0");
  Require(c.enhance.blur_sigma_px >= 0, src, "enhance.blur_sigma_px", "must be >= 0");
  Require(c.enhance.display_range_db > 0, src, "enhance.display_range_db", "must be > 0");
  static const std::set<std::string> kColormaps = {"gray", "inferno", "jet",
                                                   "viridis", "magma", "hot"};
  Require(kColormaps.count(c.enhance.colormap) > 0, src, "enhance.colormap",
          "must be one of gray, inferno, jet, viridis, magma, hot");
}

std::string ConfigToYaml(const Config& config) {
  YAML::Emitter out;
  Writer writer(out);
  Config copy = config;
  writer.Write(copy);
  return out.c_str();
}

}  // namespace uwbsar
