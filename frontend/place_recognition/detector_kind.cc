#include "frontend/place_recognition/detector_kind.h"

#include <cctype>

namespace uwbsar {

const char* DetectorName(DetectorKind kind) {
  switch (kind) {
    case DetectorKind::kSift:
      return "SIFT";
    case DetectorKind::kSurf:
      return "SURF";
    case DetectorKind::kBrisk:
      return "BRISK";
    case DetectorKind::kAkaze:
      return "AKAZE";
    case DetectorKind::kOrb:
      return "ORB";
  }
  return "?";
}

std::string DetectorColumnName(DetectorKind kind) { return EnumName(kind); }

bool ParseDetector(const std::string& name, DetectorKind* kind) {
  std::string upper = name;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (DetectorKind k : {DetectorKind::kSift, DetectorKind::kSurf, DetectorKind::kBrisk,
                         DetectorKind::kAkaze, DetectorKind::kOrb}) {
    if (upper == DetectorName(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

bool DetectorAvailable(DetectorKind kind) {
#ifdef UWBSAR_WITH_SURF
  (void)kind;
  return true;
#else
  return kind != DetectorKind::kSurf;
#endif
}

std::vector<DetectorKind> AvailableDetectors() {
  std::vector<DetectorKind> out;
  for (DetectorKind k : {DetectorKind::kSift, DetectorKind::kSurf, DetectorKind::kBrisk,
                         DetectorKind::kAkaze, DetectorKind::kOrb}) {
    if (DetectorAvailable(k)) out.push_back(k);
  }
  return out;
}

}  // namespace uwbsar
