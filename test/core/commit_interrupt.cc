#include "test/core/commit_interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>

#include "core/commit_journal.h"

namespace uwbsar::testing {
namespace {

std::atomic<int> interrupt_step{-1};
std::atomic<bool> interrupt_kills{false};

void InterruptAtChosenStep(int step) {
  if (step != interrupt_step.load()) return;
  if (interrupt_kills.load()) ::raise(SIGKILL);
  ::kill(::getpid(), SIGINT);
  // Give the signal watcher time to act while the commit goes on: it must wait for it.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
}

}  // namespace

void InterruptCommitAt(int step, bool kill) {
  interrupt_step.store(step);
  interrupt_kills.store(kill);
  SetCommitStepObserver(&InterruptAtChosenStep);
}

bool InterruptCommitAsSpecified(const char* spec) {
  int step = -1;
  char what[8] = {};
  if (spec == nullptr || std::sscanf(spec, "%d:%7s", &step, what) != 2) return false;
  InterruptCommitAt(step, std::strcmp(what, "kill") == 0);
  return true;
}

}  // namespace uwbsar::testing
