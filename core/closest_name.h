// "Did you mean": the known name closest to a mistyped one (a subcommand, an option, a
// configuration key), so that a refusal names what the user most likely meant.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace uwbsar {

/// Edits (insert, delete, replace a character, swap two neighbours) that turn `a` into `b`:
/// "mpa" is one edit from "map".
inline std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min(
          {d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}

/// The name of `names` fewest edits from `word` ("" when none is close: within a third of the
/// word's length, at least one edit and at most three); of equals, the first listed.
inline std::string ClosestName(const std::string& word, const std::vector<std::string>& names) {
  const std::size_t allowed = std::clamp<std::size_t>(word.size() / 3, 1, 3);
  std::string best;
  std::size_t best_distance = allowed + 1;
  for (const std::string& name : names) {
    const std::size_t distance = EditDistance(word, name);
    if (distance < best_distance && name != word) {
      best = name;
      best_distance = distance;
    }
  }
  return best;
}

/// " (did you mean 'NAME'?)" with the closest of `names`, or "" (ClosestName).
inline std::string DidYouMean(const std::string& word, const std::vector<std::string>& names) {
  const std::string closest = ClosestName(word, names);
  return closest.empty() ? std::string() : " (did you mean '" + closest + "'?)";
}

}  // namespace uwbsar
