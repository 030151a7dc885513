// Enums read and written by name: the configuration keeps its YAML strings (`mode:
// coherent`) while the code switches on enum values. An enum takes part by a
// specialisation of EnumNames<E> listing every value with its name:
//
//   template <>
//   struct EnumNames<ImagingMode> {
//     static constexpr std::pair<ImagingMode, const char*> kNames[] = {
//         {ImagingMode::kPaper, "paper"}, {ImagingMode::kCoherent, "coherent"}};
//   };
//
// The config loader (core/config_io.h) refuses any other name with an error that
// names the key and the allowed names.
#pragma once

#include <string>
#include <utility>

namespace uwbsar {

template <class E>
struct EnumNames;

/// The name of `value` ("" for a value missing from the table).
template <class E>
const char* EnumName(E value) {
  for (const auto& [v, name] : EnumNames<E>::kNames) {
    if (v == value) return name;
  }
  return "";
}

/// Sets `*value` to the enum named `name`; false (and `*value` unchanged) if none is.
template <class E>
bool EnumFromName(const std::string& name, E* value) {
  for (const auto& [v, n] : EnumNames<E>::kNames) {
    if (name == n) {
      *value = v;
      return true;
    }
  }
  return false;
}

/// The allowed names, comma-separated in table order ("paper, coherent").
template <class E>
std::string EnumNameList() {
  std::string out;
  for (const auto& [v, name] : EnumNames<E>::kNames) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

}  // namespace uwbsar
