#include "frontend/place_recognition/loop_rule.h"

#include <cmath>
#include <cstdio>

namespace uwbsar {
namespace {

std::string Format(const char* fmt, double a, double b) {
  char buf[160];
  std::snprintf(buf, sizeof(buf), fmt, a, b);
  return buf;
}

/// Empty when the detector's own figures pass; otherwise why not.
std::string CheckDetector(const char* name, const DetectorStats& s, const LoopValidationConfig& c) {
  const std::string n = name;
  if (s.good_matches <= c.min_good_matches) {
    return n +
           Format(": %.0f good matches, need more than %.0f", s.good_matches, c.min_good_matches);
  }
  if (!s.has_transform) return n + ": no transform";
  if (!std::isfinite(s.scale) || !std::isfinite(s.tx_px) || !std::isfinite(s.ty_px) ||
      !std::isfinite(s.rotation_deg)) {
    return n + ": non-finite transform";
  }
  if (s.scale < c.min_scale || s.scale > c.max_scale) {
    char buf[160];
    std::snprintf(buf, sizeof(buf), ": scale %.3f outside [%.3f, %.3f]", s.scale, c.min_scale,
                  c.max_scale);
    return n + buf;
  }
  return "";
}

}  // namespace

double WrapDegrees(double deg) {
  double a = std::fmod(deg + 180.0, 360.0);
  if (a < 0) a += 360.0;
  return a - 180.0;
}

DetectorStats StatsOf(const MatchResult& m) {
  DetectorStats s;
  s.good_matches = m.good_matches;
  s.has_transform = m.has_transform;
  s.scale = m.scale;
  s.tx_px = m.tx_px;
  s.ty_px = m.ty_px;
  s.rotation_deg = m.rotation_deg;
  return s;
}

LoopDecision ApplyLoopRule(const DetectorStats& akaze, const DetectorStats& orb,
                           const LoopValidationConfig& c) {
  LoopDecision d;
  d.reason = CheckDetector("AKAZE", akaze, c);
  if (d.reason.empty()) d.reason = CheckDetector("ORB", orb, c);
  if (!d.reason.empty()) return d;
  const double dtx = std::abs(akaze.tx_px - orb.tx_px);
  const double dty = std::abs(akaze.ty_px - orb.ty_px);
  const double drot = WrapDegrees(orb.rotation_deg - akaze.rotation_deg);
  if (dtx > c.max_tx_difference_px) {
    d.reason =
        Format("AKAZE and ORB disagree: |dtx| %.1f px > %.1f px", dtx, c.max_tx_difference_px);
  } else if (dty > c.max_ty_difference_px) {
    d.reason =
        Format("AKAZE and ORB disagree: |dty| %.1f px > %.1f px", dty, c.max_ty_difference_px);
  } else if (std::abs(drot) > c.max_rotation_difference_deg) {
    d.reason = Format("AKAZE and ORB disagree: |drot| %.1f deg > %.1f deg", std::abs(drot),
                      c.max_rotation_difference_deg);
  }
  if (!d.reason.empty()) return d;
  // Paper: T = (n_a T_a + n_o T_o) / (n_a + n_o) over (tx, ty, rot); the rotation is
  // averaged as an offset from AKAZE's so that +179 and -179 deg fuse to 180, not 0.
  const double na = akaze.good_matches, no = orb.good_matches;
  const double wo = no / (na + no);
  d.tx_px = (na * akaze.tx_px + no * orb.tx_px) / (na + no);
  d.ty_px = (na * akaze.ty_px + no * orb.ty_px) / (na + no);
  d.rotation_deg = WrapDegrees(akaze.rotation_deg + wo * drot);
  d.accepted = true;
  return d;
}

}  // namespace uwbsar
