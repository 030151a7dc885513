#include "core/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace uwbsar {
namespace {
std::atomic<int> g_level{static_cast<int>(LogLevel::kInfo)};
std::mutex g_mutex;
}  // namespace

void SetLogLevel(LogLevel level) { g_level = static_cast<int>(level); }
LogLevel GetLogLevel() { return static_cast<LogLevel>(g_level.load()); }

void Log(LogLevel level, const std::string& message) {
  if (static_cast<int>(level) < g_level.load()) return;
  static const char* kNames[] = {"debug", "info", "warning", "error"};
  std::lock_guard<std::mutex> lock(g_mutex);
  std::fprintf(stderr, "uwbsar: %s: %s\n", kNames[static_cast<int>(level)], message.c_str());
}

void LogOnce::Warn(const std::string& key, const std::string& message) {
  const std::string token = "\n" + key + "\n";
  if (seen_.find(token) != std::string::npos) return;
  seen_ += token.substr(0, token.size() - 1);
  seen_ += "\n";
  Log(LogLevel::kWarning, message + " (further occurrences are only counted)");
}

}  // namespace uwbsar
