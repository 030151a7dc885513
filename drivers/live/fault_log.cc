#include "drivers/live/fault_log.h"

#include "core/log.h"

namespace uwbsar::live {

void FaultLog::set_listener(Listener listener) {
  std::lock_guard<std::mutex> lock(mutex_);
  listener_ = std::move(listener);
}

void FaultLog::Report(const std::string& kind, const std::string& detail, long long count) {
  if (count <= 0) return;
  Listener listener;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    long long& n = counts_[kind];
    if (n == 0) {
      Log(LogLevel::kWarning, kind + ": " + detail + " (further occurrences are counted)");
    }
    n += count;
    listener = listener_;
  }
  if (listener) listener(kind, detail);
}

std::map<std::string, long long> FaultLog::Counts() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counts_;
}

long long FaultLog::Count(const std::string& kind) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = counts_.find(kind);
  return it == counts_.end() ? 0 : it->second;
}

}  // namespace uwbsar::live
