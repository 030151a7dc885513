#include "drivers/live/thread_priority.h"

#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <cstring>

#include "core/log.h"

namespace uwbsar::live {

std::string SetCurrentThreadRealtime(int priority) {
  if (priority <= 0) return "";
  const int lo = sched_get_priority_min(SCHED_FIFO);
  const int hi = sched_get_priority_max(SCHED_FIFO);
  if (priority < lo || priority > hi) {
    return "priority " + std::to_string(priority) + " outside SCHED_FIFO's " + std::to_string(lo) +
           ".." + std::to_string(hi);
  }
  sched_param param{};
  param.sched_priority = priority;
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (rc != 0)
    return std::string("SCHED_FIFO ") + std::to_string(priority) + ": " + std::strerror(rc);
  return "";
}

void RequestRealtimeOrWarn(int priority, const std::string& who) {
  const std::string error = SetCurrentThreadRealtime(priority);
  if (error.empty()) return;
  static std::atomic<bool> warned{false};
  if (warned.exchange(true)) return;
  Log(LogLevel::kWarning, who + ": " + error +
                              "; device threads run at normal priority and may poll late on a "
                              "busy machine (live.driver_priority: 0 silences this)");
}

}  // namespace uwbsar::live
