// Faults of the live link (unplugs, garbage, broken frames, stalls, clock steps):
// each kind is logged once when it first happens and counted every time, so a
// flaky cable cannot flood the console; the counts go into the run's summary.
// Every report is also passed to an optional listener (the recording's event topic).
// Thread-safe: drivers report from their own threads.
#pragma once

#include <functional>
#include <map>
#include <mutex>
#include <string>

namespace uwbsar::live {

class FaultLog {
 public:
  using Listener = std::function<void(const std::string& kind, const std::string& detail)>;

  void set_listener(Listener listener);
  /// Counts one occurrence of `kind` (e.g. "radar left: unplugged"); logs it the first time.
  void Report(const std::string& kind, const std::string& detail, long long count = 1);
  std::map<std::string, long long> Counts() const;
  long long Count(const std::string& kind) const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, long long> counts_;
  Listener listener_;
};

}  // namespace uwbsar::live
