// The progress bar of the commands that run for seconds (`map`, `demo`, `simulate`,
// `localize`, `detectors`, `merge`): one line on stderr, "[#####     ]  42% of 80 s of log",
// redrawn at most 5 times a second and ended with a newline. Drawn when the command wants it
// (not -q) and stderr is a terminal; UWBSAR_PROGRESS=1 draws it anyway (a log file, a test),
// UWBSAR_PROGRESS=0 never.
#pragma once

#include <chrono>
#include <string>

#include "core/types.h"

namespace uwbsar::slam {

class ProgressBar {
 public:
  /// `what` follows the percentage ("of 80 s of log").
  ProgressBar(bool wanted, std::string what);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// `fraction` of the work done (clamped to [0, 1]); `stage` (optional) names the part
  /// under way when the work has several ("matching regions").
  void Update(double fraction, const std::string& stage = "");
  /// Update() with the share of [start_ns, end_ns] that `now_ns` has reached, in doubles (a
  /// damaged bag's stamps can be anything, and must not overflow).
  void UpdateStamp(TimestampNs now_ns, TimestampNs start_ns, TimestampNs end_ns);
  bool enabled() const { return enabled_; }

 private:
  bool enabled_;
  std::string what_;
  bool drawn_ = false;
  int width_ = 0;  ///< of the longest text drawn after the percentage
  std::chrono::steady_clock::time_point last_;
};

/// Whether a bar is drawn for a command that wants one: the UWBSAR_PROGRESS override, else
/// whether stderr is a terminal.
bool ProgressWanted(bool wanted);

}  // namespace uwbsar::slam
