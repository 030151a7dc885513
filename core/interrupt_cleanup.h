// Ctrl-C must not leave a command's private files behind (staging folders, decompressed
// temporaries): those register here while they exist, and the interrupt watcher removes
// them before the process ends on SIGINT/SIGTERM. A command that finishes cleanly on a
// signal instead (live `run`) sets its own handler.
#pragma once

#include <functional>
#include <string>

namespace uwbsar {

/// Registers `path` (a file or folder) for removal on SIGINT/SIGTERM while this object
/// lives. It does not remove the path when destroyed: the owner does, on its own exit paths.
class RemoveOnInterrupt {
 public:
  explicit RemoveOnInterrupt(std::string path);
  ~RemoveOnInterrupt();
  RemoveOnInterrupt(const RemoveOnInterrupt&) = delete;
  RemoveOnInterrupt& operator=(const RemoveOnInterrupt&) = delete;

 private:
  long id_;
};

/// Holds back the end of the process on SIGINT/SIGTERM while this object lives (a commit
/// that must complete once begun, core/commit_journal.h): the watcher waits for every
/// DeferInterrupts to end before it removes the registered paths and ends the process. When
/// the watcher is already ending the process, the constructor does not return.
class DeferInterrupts {
 public:
  DeferInterrupts();
  ~DeferInterrupts();
  DeferInterrupts(const DeferInterrupts&) = delete;
  DeferInterrupts& operator=(const DeferInterrupts&) = delete;
};

/// Blocks SIGINT and SIGTERM in the calling thread (and so in every thread it starts later)
/// and starts a thread that waits for them. On a signal it calls the handler set with
/// SetInterruptHandler when there is one; otherwise it removes every registered path and
/// ends the process with the signal (exit status 128 + signal, as without the watcher).
/// A signal that was ignored when the process started stays ignored. Call once, first thing
/// in main(). Without it registrations are harmless no-ops.
void InstallInterruptCleanup();

/// Replaces the default action (clean up and end) by `handler`, e.g. to stop a live run.
void SetInterruptHandler(std::function<void()> handler);

}  // namespace uwbsar
