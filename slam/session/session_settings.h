// What joining and localising in saved sessions are given: the core sections (place
// recognition, backend, imaging geometry) and session.*, their own section. Built from the
// whole file's struct (slam/app_config.h), or any struct with those members.
#pragma once

#include "slam/config/system_config.h"
#include "slam/session/session_config.h"

namespace uwbsar {

struct SessionSettings : SystemConfig {
  SessionConfig session;

  SessionSettings() = default;
  /// From any configuration holding the core sections and `session` (implicit on purpose).
  template <class WholeConfig>
  SessionSettings(const WholeConfig& config)  // NOLINT(google-explicit-constructor)
      : SystemConfig(config), session(config.session) {}
};

}  // namespace uwbsar
