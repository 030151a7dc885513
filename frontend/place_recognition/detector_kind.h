// Which feature detector: the five of the paper, by enum in the code and by name in the
// configuration (`place_recognition.validation.detectors: [akaze, orb]`), in reports and in
// session files ("AKAZE"). Features, matches and good-match counts are kept per detector
// (DetectorMap), so that the detectors a configuration names decide what is computed.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/named_enum.h"

namespace uwbsar {

enum class DetectorKind { kSift, kSurf, kBrisk, kAkaze, kOrb };

/// The configuration's names (lower case; ParseDetector takes any case).
template <>
struct EnumNames<DetectorKind> {
  static constexpr std::pair<DetectorKind, const char*> kNames[] = {{DetectorKind::kSift, "sift"},
                                                                    {DetectorKind::kSurf, "surf"},
                                                                    {DetectorKind::kBrisk, "brisk"},
                                                                    {DetectorKind::kAkaze, "akaze"},
                                                                    {DetectorKind::kOrb, "orb"}};
};

/// One value per detector (features, matches, good-match counts): only the detectors that
/// were run have an entry.
template <class T>
using DetectorMap = std::map<DetectorKind, T>;

/// The paper's validation pair: AKAZE, then ORB.
inline std::vector<DetectorKind> PaperDetectorPair() {
  return {DetectorKind::kAkaze, DetectorKind::kOrb};
}

/// "SIFT", "SURF", "BRISK", "AKAZE", "ORB".
const char* DetectorName(DetectorKind kind);
/// Lower case ("akaze"): column names of CSV files (loops.csv, loop statistics).
std::string DetectorColumnName(DetectorKind kind);
/// Case-insensitive; false for an unknown name.
bool ParseDetector(const std::string& name, DetectorKind* kind);
/// False for SURF when the project was built without UWBSAR_WITH_SURF.
bool DetectorAvailable(DetectorKind kind);
/// The paper's order (SIFT, SURF, BRISK, AKAZE, ORB), only those available.
std::vector<DetectorKind> AvailableDetectors();

/// `map`'s value for `kind`, or `fallback` when that detector was not run.
template <class T>
const T& Of(const DetectorMap<T>& map, DetectorKind kind, const T& fallback) {
  auto it = map.find(kind);
  return it == map.end() ? fallback : it->second;
}

}  // namespace uwbsar
