#include "frontend/place_recognition/loop_rule.h"

#include <cassert>
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

LoopDecision ApplyLoopRule(const DetectorStats& first, const DetectorStats& second,
                           const LoopValidationConfig& c) {
  assert(c.detectors.size() == 2);
  const std::string name_a = DetectorName(c.detectors[0]);
  const std::string name_b = DetectorName(c.detectors[1]);
  const std::string pair = name_a + " and " + name_b + " disagree: ";
  LoopDecision d;
  d.reason = CheckDetector(name_a.c_str(), first, c);
  if (d.reason.empty()) d.reason = CheckDetector(name_b.c_str(), second, c);
  if (!d.reason.empty()) return d;
  const double dtx = std::abs(first.tx_px - second.tx_px);
  const double dty = std::abs(first.ty_px - second.ty_px);
  const double drot = WrapDegrees(second.rotation_deg - first.rotation_deg);
  if (dtx > c.max_tx_difference_px) {
    d.reason = pair + Format("|dtx| %.1f px > %.1f px", dtx, c.max_tx_difference_px);
  } else if (dty > c.max_ty_difference_px) {
    d.reason = pair + Format("|dty| %.1f px > %.1f px", dty, c.max_ty_difference_px);
  } else if (std::abs(drot) > c.max_rotation_difference_deg) {
    d.reason =
        pair + Format("|drot| %.1f deg > %.1f deg", std::abs(drot), c.max_rotation_difference_deg);
  }
  if (!d.reason.empty()) return d;
  // Paper: T = (n_a T_a + n_o T_o) / (n_a + n_o) over (tx, ty, rot); the rotation is
  // averaged as an offset from the first detector's so that +179 and -179 deg fuse to 180,
  // not 0.
  const double na = first.good_matches, nb = second.good_matches;
  const double wb = nb / (na + nb);
  d.tx_px = (na * first.tx_px + nb * second.tx_px) / (na + nb);
  d.ty_px = (na * first.ty_px + nb * second.ty_px) / (na + nb);
  d.rotation_deg = WrapDegrees(first.rotation_deg + wb * drot);
  d.accepted = true;
  return d;
}

}  // namespace uwbsar
