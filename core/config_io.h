// YAML <-> configuration structs. Any struct with a Visit(V&) listing its fields can be
// read and written; unknown keys and wrong types are errors that name the file, the line
// and the dotted key. YAML is parsed here and nowhere else. Each section's struct and its
// Validate() sit beside the code that owns them; the whole file's struct (slam/app_config.h)
// and its loader (slam/app_config_io.h) assemble them.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/closest_name.h"
#include "core/errors.h"
#include "core/named_enum.h"
#include "core/shortest_number.h"
#include "core/yaml_document.h"

namespace uwbsar {

/// Bad configuration input (file, key, value). what() is a complete one-line message.
class ConfigError : public InputError {
 public:
  using InputError::InputError;
};

/// Where each key of a configuration was last set: the dotted key as messages name it (an item
/// of a list merged by name as `radars[NAME]`) -> "file:line". Validation messages name the line
/// of the key they refuse (slam/app_config_io.cc).
using ConfigOrigins = std::map<std::string, std::string>;

namespace config_yaml {

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

/// An optional value is written `null` when it has none (and read so from null, ~ or nothing).
template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};

/// A list whose items have a `name` and declare kListAddRequires is merged by name when read
/// over a list in effect, not replaced (see Reader::MergeByName).
template <class T, class = void>
struct MergesByName : std::false_type {};
template <class T>
struct MergesByName<std::vector<T>,
                    std::void_t<decltype(T::kListAddRequires), decltype(std::declval<T&>().name)>>
    : std::true_type {};

inline std::string Where(const std::string& source, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  std::ostringstream out;
  out << source;
  if (mark.line >= 0) out << ":" << (mark.line + 1);
  return out.str();
}

/// Reads a YAML mapping into a struct, recording which keys it knows and, given `origins`,
/// where each key it reads is set.
class Reader {
 public:
  Reader(const YAML::Node& node, std::string source, std::string prefix,
         ConfigOrigins* origins = nullptr)
      : node_(node), source_(std::move(source)), prefix_(std::move(prefix)), origins_(origins) {}

  template <class T>
  void operator()(const char* key, T& value) {
    known_.insert(key);
    const YAML::Node child = node_[key];
    if (child) Read(child, value, prefix_ + key);
  }

  /// Throws if the mapping holds a key that no field claimed.
  void CheckUnknownKeys() const {
    for (const auto& kv : node_) {
      if (!kv.first.IsScalar()) {
        throw ConfigError(Where(source_, kv.first) + ": a key in '" +
                          (prefix_.empty() ? std::string("the top level")
                                           : prefix_.substr(0, prefix_.size() - 1)) +
                          "' is not a plain name (complex key)");
      }
      const std::string key = kv.first.Scalar();
      if (!known_.count(key)) {
        std::vector<std::string> known;
        for (const std::string& k : known_) known.push_back(prefix_ + k);
        throw ConfigError(Where(source_, kv.first) + ": unknown key '" + prefix_ + key + "'" +
                          DidYouMean(prefix_ + key, known));
      }
    }
  }

  template <class T>
  void Read(const YAML::Node& node, T& value, const std::string& key) {
    if (origins_) (*origins_)[key] = Where(source_, node);
    if constexpr (HasVisit<T>::value) {
      if (!node.IsMap())
        throw ConfigError(Where(source_, node) + ": '" + key + "' must be a mapping");
      Reader nested(node, source_, key + ".", origins_);
      value.Visit(nested);
      nested.CheckUnknownKeys();
    } else if constexpr (MergesByName<T>::value) {
      MergeByName(node, value, key);
    } else if constexpr (IsVector<T>::value) {
      if (!node.IsSequence()) {
        throw ConfigError(Where(source_, node) + ": '" + key + "' must be a list");
      }
      T items(node.size());
      Forget(key + "[");  // the items of the list it replaces
      for (std::size_t i = 0; i < node.size(); ++i) {
        Read(node[i], items[i], key + "[" + std::to_string(i) + "]");
      }
      value = std::move(items);
    } else if constexpr (IsOptional<T>::value) {
      if (node.IsNull()) {
        value.reset();
      } else {
        typename T::value_type given{};
        Read(node, given, key);
        value = given;
      }
    } else if constexpr (std::is_enum_v<T>) {
      if (!node.IsScalar() || !EnumFromName(node.Scalar(), &value)) {
        throw ConfigError(Where(source_, node) + ": '" + key + "' must be one of " +
                          EnumNameList<T>() +
                          (node.IsScalar() ? ", got '" + node.Scalar() + "'" : std::string()));
      }
    } else {
      if (!node.IsScalar())
        throw ConfigError(Where(source_, node) + ": '" + key + "' must be a value");
      if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
        if (HasLeadingZero(node.Scalar())) {
          throw ConfigError(Where(source_, node) + ": '" + key + "' has value '" + node.Scalar() +
                            "' with a leading zero (octal in YAML 1.1, decimal in 1.2): write "
                            "it without the zero");
        }
      }
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
  /// Each entry names the item it changes (only the keys it gives), adds (a new name: the
  /// item's defaults, and it must give T::kListAddRequires) or removes (`remove: true`, and
  /// nothing else but the name); a list that adds must name every item in effect. An empty
  /// list or an entry without a name is refused: either would otherwise change nothing,
  /// silently.
  template <class T>
  void MergeByName(const YAML::Node& node, std::vector<T>& items, const std::string& key) {
    if (!node.IsSequence())
      throw ConfigError(Where(source_, node) + ": '" + key + "' must be a list");
    if (node.size() == 0) {
      throw ConfigError(Where(source_, node) + ": '" + key +
                        "' is empty; its entries change, add or remove items by name (remove "
                        "one with {name: NAME, remove: true})");
    }
    std::set<std::string> seen;
    std::string added_at;             // where the list first adds an item
    std::vector<std::string> before;  // the names in effect before this list
    for (const T& item : items) before.push_back(item.name);
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node entry = node[i];
      const std::string entry_key = key + "[" + std::to_string(i) + "]";
      const std::string at = Where(source_, entry) + ": '" + entry_key + "'";
      if (!entry.IsMap()) throw ConfigError(at + " must be a mapping");
      const YAML::Node name = entry["name"];
      if (!name || !name.IsScalar() || name.Scalar().empty()) {
        throw ConfigError(at + " has no 'name': entries of '" + key +
                          "' change, add or remove the item of that name");
      }
      const std::string n = name.Scalar();
      if (!seen.insert(n).second) throw ConfigError(at + " names '" + n + "' a second time");
      auto it = std::find_if(items.begin(), items.end(), [&](const T& t) { return t.name == n; });
      if (const YAML::Node remove = entry["remove"]) {
        bool yes = false;
        if (!remove.IsScalar() || !YAML::convert<bool>::decode(remove, yes) || !yes) {
          throw ConfigError(Where(source_, remove) + ": '" + entry_key +
                            ".remove' must be true (leave it out to change '" + n + "')");
        }
        if (entry.size() != 2) {
          throw ConfigError(at + " removes '" + n + "' and gives only name and remove");
        }
        if (it == items.end()) throw ConfigError(at + " removes '" + n + "', which is not listed");
        items.erase(it);
        Forget(key + "[" + n + "]");
      } else if (it != items.end()) {
        Read(entry, *it, key + "[" + n + "]");  // only the keys it gives
      } else {
        T added;
        Read(entry, added, key + "[" + n + "]");
        if (!entry[T::kListAddRequires]) {
          throw ConfigError(at + " adds '" + n + "' (no item of that name) and must give '" +
                            T::kListAddRequires + "'");
        }
        items.push_back(std::move(added));
        added_at = added_at.empty() ? at + " adds '" + n + "'" : added_at;
      }
    }
    // A list that adds an item names every item it keeps: a file written as the whole list
    // (one radar of another name) would otherwise run with the defaults beside it, silently.
    std::string unnamed;
    for (const std::string& n : before) {
      if (!seen.count(n)) unnamed += (unnamed.empty() ? "'" : ", '") + n + "'";
    }
    if (!added_at.empty() && !unnamed.empty()) {
      throw ConfigError(added_at + " beside " + unnamed +
                        ", which this list does not name: keep each with '- name: NAME' or "
                        "remove it with '- {name: NAME, remove: true}'");
    }
  }

  /// Drops the origins of the keys under `prefix` (a list replaced, an item removed).
  void Forget(const std::string& prefix) {
    if (!origins_) return;
    for (auto it = origins_->lower_bound(prefix);
         it != origins_->end() && it->first.compare(0, prefix.size(), prefix) == 0;) {
      it = origins_->erase(it);
    }
  }

  const YAML::Node& node_;
  std::string source_;
  std::string prefix_;
  ConfigOrigins* origins_;
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
    } else if constexpr (IsOptional<T>::value) {
      if (value) {
        Write(*value);
      } else {
        out_ << YAML::Null;
      }
    } else if constexpr (std::is_enum_v<T>) {
      out_ << EnumName(value);
    } else if constexpr (std::is_floating_point_v<T>) {
      // yaml-cpp's own form has 17 digits (0.59999999999999998); the shortest reads back the same.
      if (std::isfinite(value)) {
        out_ << ShortestNumber(value);
      } else {
        out_ << value;
      }
    } else {
      out_ << value;
    }
  }

 private:
  YAML::Emitter& out_;
};

}  // namespace config_yaml

/// As ReadConfigYaml, over `base` instead of the defaults: the keys of the text replace
/// base's, a list as a whole except one merged by name (MergesByName: radars), repeated
/// --config files merged in order, later wins. Given `origins`, each key the text sets is
/// recorded there with its file and line (over those of earlier files).
template <class T>
T ReadConfigYamlOver(const std::string& yaml_text, const std::string& source_name, T base,
                     ConfigOrigins* origins = nullptr) {
  YAML::Node root;
  try {
    root = ParseYamlDocument(yaml_text, source_name);
  } catch (const ConfigError&) {
    throw;
  } catch (const InputError& e) {
    throw ConfigError(e.what());
  }
  T config = std::move(base);
  if (root.IsNull()) return config;  // an empty file changes nothing
  if (!root.IsMap()) throw ConfigError(source_name + ": the top level must be a mapping");
  try {
    config_yaml::Reader reader(root, source_name, "", origins);
    config.Visit(reader);
    reader.CheckUnknownKeys();
  } catch (const YAML::Exception& e) {
    // A shape the reader did not foresee is still bad input naming the file and line.
    throw ConfigError(source_name +
                      (e.mark.line >= 0 ? ":" + std::to_string(e.mark.line + 1) : "") +
                      ": unexpected YAML shape: " + e.msg);
  }
  return config;
}

/// Reads YAML text over the defaults of `T` (a struct with Visit): keys that are absent keep
/// their default; an empty text means all defaults. No semantic checks. Throws ConfigError
/// on syntax errors, duplicate keys, a second document (ParseYamlDocument), unknown keys,
/// wrong types and numbers with a leading zero; `source_name` is used in messages.
template <class T>
T ReadConfigYaml(const std::string& yaml_text, const std::string& source_name,
                 ConfigOrigins* origins = nullptr) {
  return ReadConfigYamlOver(yaml_text, source_name, T{}, origins);
}

/// The configuration (any struct with Visit) as YAML: every field, no comments, e.g. for
/// run summaries.
template <class T>
std::string ConfigToYaml(const T& config) {
  YAML::Emitter out;
  config_yaml::Writer writer(out);
  T copy = config;
  writer.Write(copy);
  return out.c_str();
}

}  // namespace uwbsar
