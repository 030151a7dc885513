// Reading a YAML file that must hold a mapping (map_server maps, grid files, the
// configuration): one place for the open / syntax / shape errors, each naming the file (and
// line). Every YAML file uwbsar reads as input is parsed by ParseYamlDocument: a duplicate key,
// a second document and a number with a leading zero are refused, never silently resolved.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <type_traits>

#include "core/bounded_file.h"
#include "core/errors.h"
#include "core/yaml_document.h"

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
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    if (node.IsScalar() && HasLeadingZero(node.Scalar())) {
      throw InputError(YamlWhere(file, node) + ": " + what + " key '" + key + "' has value '" +
                       node.Scalar() +
                       "' with a leading zero (octal in YAML 1.1, decimal in 1.2): write it "
                       "without the zero");
    }
  }
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
/// kMaxYamlFileBytes, is not valid YAML (ParseYamlDocument) or is not a mapping.
inline YAML::Node LoadYamlMappingFile(const std::string& path, const std::string& what) {
  const YAML::Node root = ParseYamlDocument(ReadBoundedFile(path, what), path);
  if (!root.IsMap()) throw InputError(path + ": a " + what + " file must be a YAML mapping");
  return root;
}

}  // namespace uwbsar
