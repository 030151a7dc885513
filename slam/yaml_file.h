// Reading a YAML file that must hold a mapping (map_server maps, grid files):
// one place for the open / syntax / shape errors, each naming the file (and line).
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "slam/bounded_file.h"
#include "slam/errors.h"

namespace uwbsar {

/// "file:line" of a node (just "file" when the node has no position).
inline std::string YamlWhere(const std::string& file, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.line >= 0 ? file + ":" + std::to_string(mark.line + 1) : file;
}

/// The value of `node` as T; InputError naming file, line and "<what> key '<key>'" if not.
template <class T>
T YamlValue(const std::string& file, const YAML::Node& node, const char* key,
            const std::string& what) {
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    throw InputError(YamlWhere(file, node) + ": " + what + " key '" + key +
                     "' has invalid value '" +
                     (node.IsScalar() ? node.Scalar() : std::string("<not a value>")) + "'");
  }
}

/// The file's root mapping. `what` names the kind of file in messages ("map", "grid").
/// Throws InputError when the file cannot be opened, is not a regular file, is larger than
/// kMaxYamlFileBytes, is not valid YAML or is not a mapping.
inline YAML::Node LoadYamlMappingFile(const std::string& path, const std::string& what) {
  const std::string text = ReadBoundedFile(path, what);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(path + ":" + std::to_string(e.mark.line + 1) +
                     ": YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) throw InputError(path + ": a " + what + " file must be a YAML mapping");
  return root;
}

}  // namespace uwbsar
