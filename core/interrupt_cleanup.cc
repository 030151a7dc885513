#include "core/interrupt_cleanup.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>

#include <condition_variable>
#include <filesystem>
#include <map>
#include <mutex>
#include <thread>

namespace uwbsar {
namespace {

struct Registry {
  std::mutex mutex;
  std::map<long, std::string> paths;
  long next_id = 0;
  std::function<void()> handler;
  int deferring = 0;         ///< live DeferInterrupts
  bool terminating = false;  ///< the watcher is ending the process
  std::condition_variable deferred_done;
};

Registry& TheRegistry() {
  static Registry* registry = new Registry;  // never destroyed: the watcher may outlive main
  return *registry;
}

/// Removes `path` while other threads may still be writing into it (the process goes on until
/// the watcher ends it): renamed away first, never onto a name that exists, so that no file
/// they create by name afterwards lands in it. A creation already on its way when it was
/// renamed may still land: removed again until it is gone (a few passes at most).
void RemoveWhileWritten(const std::string& path) {
  const std::string doomed = path + ".removing";
  const bool renamed =
      ::renameat2(AT_FDCWD, path.c_str(), AT_FDCWD, doomed.c_str(), RENAME_NOREPLACE) == 0;
  std::error_code ec;
  for (int pass = 0; pass < 100; ++pass) {
    std::filesystem::remove_all(renamed ? doomed : path, ec);
    if (!ec) return;
  }
}

void WatchSignals(sigset_t set) {
  for (;;) {
    int sig = 0;
    if (sigwait(&set, &sig) != 0) continue;
    Registry& r = TheRegistry();
    std::function<void()> handler;
    {
      std::unique_lock<std::mutex> lock(r.mutex);
      handler = r.handler;
      if (!handler) {
        r.terminating = true;
        r.deferred_done.wait(lock, [&r] { return r.deferring == 0; });
        for (const auto& [id, path] : r.paths) RemoveWhileWritten(path);
        r.paths.clear();
      }
    }
    if (handler) {
      handler();
      continue;
    }
    // End as the signal would have ended the process without the watcher.
    ::signal(sig, SIG_DFL);
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, sig);
    pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
    ::raise(sig);
  }
}

}  // namespace

RemoveOnInterrupt::RemoveOnInterrupt(std::string path) {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  id_ = r.next_id++;
  r.paths[id_] = std::move(path);
}

RemoveOnInterrupt::~RemoveOnInterrupt() {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.paths.erase(id_);
}

DeferInterrupts::DeferInterrupts() {
  Registry& r = TheRegistry();
  std::unique_lock<std::mutex> lock(r.mutex);
  // The process is ending on a signal: beginning a commit now could remove old outputs whose
  // successors the watcher is deleting. Wait for the end instead.
  while (r.terminating) r.deferred_done.wait(lock);
  ++r.deferring;
}

DeferInterrupts::~DeferInterrupts() {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (--r.deferring == 0) r.deferred_done.notify_all();
}

void InstallInterruptCleanup() {
  sigset_t set;
  sigemptyset(&set);
  for (const int sig : {SIGINT, SIGTERM}) {
    // A signal the process was started with ignored (a background job of a script, nohup)
    // stays ignored, as without the watcher.
    struct sigaction current {};
    if (sigaction(sig, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    sigaddset(&set, sig);
  }
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread(WatchSignals, set).detach();
}

void SetInterruptHandler(std::function<void()> handler) {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.handler = std::move(handler);
}

}  // namespace uwbsar
