// Numbers as text in the shortest form that reads back to the same value (0.6 is "0.6",
// not "0.59999999999999998"): what `uwbsar config` and the configuration files print.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <string>
#include <system_error>
#include <type_traits>

namespace uwbsar {

/// `value` in the shortest decimal (or exponent) form that parses back exactly.
template <class T>
std::string ShortestNumber(T value) {
  static_assert(std::is_floating_point_v<T>);
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof(buf), value);
  if (r.ec != std::errc()) return std::to_string(value);
  std::string text(buf, r.ptr);
  // The plain form while it is not much longer: 7290000000 reads better than 7.29e+09.
  char fixed[400];
  const std::to_chars_result f =
      std::to_chars(fixed, fixed + sizeof(fixed), value, std::chars_format::fixed);
  if (f.ec == std::errc() && f.ptr - fixed <= static_cast<std::ptrdiff_t>(text.size()) + 5) {
    return std::string(fixed, f.ptr);
  }
  // "1e-05" is a string to YAML 1.1 readers (PyYAML): "1.0e-05" is a number to every reader.
  const std::size_t e = text.find('e');
  if (e != std::string::npos && text.find('.') == std::string::npos) text.insert(e, ".0");
  return text;
}

/// `value` rounded to `digits` significant digits (a measured figure printed as a key whose
/// last digits would be noise).
inline double RoundToDigits(double value, int digits) {
  if (!std::isfinite(value)) return value;
  char buf[64];
  const std::to_chars_result r =
      std::to_chars(buf, buf + sizeof(buf), value, std::chars_format::general, digits);
  if (r.ec != std::errc()) return value;
  *r.ptr = '\0';
  return std::strtod(buf, nullptr);
}

}  // namespace uwbsar
