#include "slam/session/session_config.h"

#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

/// Joining and localising in saved sessions.
void Validate(const SessionConfig& s, const std::string& src) {
  Require(s.connect_min_loops >= 1, src, "session.connect_min_loops", "must be >= 1");
  Require(s.connect_agree_m > 0, src, "session.connect_agree_m", "must be > 0");
  Require(s.connect_agree_deg > 0, src, "session.connect_agree_deg", "must be > 0");
  Require(s.search_radius_m > 0, src, "session.search_radius_m", "must be > 0");
  Require(s.localize_lost_after_m > 0, src, "session.localize_lost_after_m", "must be > 0");
  Require(s.localize_window_keyframes >= 2, src, "session.localize_window_keyframes",
          "must be >= 2");
  Require(s.odometry_spacing_m >= 0 && s.odometry_spacing_m <= 100, src,
          "session.odometry_spacing_m", "must be in [0, 100]");
}

}  // namespace uwbsar
