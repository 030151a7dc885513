// Minimal leveled logging to stderr. Rejections of bad input are counted in
// stats structs and logged once per kind (LogOnce) so a noisy sensor cannot
// flood the console.
#pragma once

#include <string>

namespace uwbsar {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarning = 2, kError = 3, kSilent = 4 };

void SetLogLevel(LogLevel level);
LogLevel GetLogLevel();
void Log(LogLevel level, const std::string& message);

/// Logs `message` the first time `key` is seen by this `once` set; later calls are dropped.
class LogOnce {
 public:
  void Warn(const std::string& key, const std::string& message);

 private:
  std::string seen_;  // '\n'-separated keys; tiny sets, no need for a hash set
};

}  // namespace uwbsar
