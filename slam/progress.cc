#include "slam/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <utility>

namespace uwbsar::slam {

bool ProgressWanted(bool wanted) {
  if (!wanted) return false;
  const char* env = std::getenv("UWBSAR_PROGRESS");
  if (env != nullptr && std::string(env) == "1") return true;
  if (env != nullptr && std::string(env) == "0") return false;
  return ::isatty(2) != 0;
}

ProgressBar::ProgressBar(bool wanted, std::string what)
    : enabled_(ProgressWanted(wanted)), what_(std::move(what)) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fprintf(stderr, "\n");
}

void ProgressBar::Update(double fraction, const std::string& stage) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_ < std::chrono::milliseconds(200)) return;
  last_ = now;
  drawn_ = true;
  const double f = std::clamp(fraction, 0.0, 1.0);
  const int filled = static_cast<int>(f * 30);
  const std::string text = what_ + (stage.empty() ? "" : ": " + stage);
  // Padded to the longest line drawn: a shorter one must not leave the end of the last.
  width_ = std::max(width_, static_cast<int>(text.size()));
  std::fprintf(stderr, "\r[%.*s%*s] %3.0f%% %-*s", filled, "##############################",
               30 - filled, "", 100 * f, width_, text.c_str());
  std::fflush(stderr);
}

void ProgressBar::UpdateStamp(TimestampNs now_ns, TimestampNs start_ns, TimestampNs end_ns) {
  if (!enabled_ || end_ns <= start_ns) return;
  const double span = static_cast<double>(end_ns) - static_cast<double>(start_ns);
  Update((static_cast<double>(now_ns) - static_cast<double>(start_ns)) / span);
}

}  // namespace uwbsar::slam
