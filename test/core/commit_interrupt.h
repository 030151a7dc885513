// Interrupting a commit at a chosen step, for the interruption tests: the commit journal's
// unit test (test/core/commit_journal_test.cc, in a child process) and the test build of the
// command (test/tools/arm_commit_interrupt.cc, for test/slam/session/session_safety_cli_test.cc).
// Installed through the journal's seam (SetCommitStepObserver), so the shipped binary has none.
#pragma once

namespace uwbsar::testing {

/// The environment variable that arms the test build of the command: `<step>:<kill|int>`.
constexpr const char* kInterruptCommitVariable = "UWBSAR_TEST_INTERRUPT_COMMIT";

/// From now on this process sends itself SIGKILL (`kill`) or SIGINT (otherwise) at step `step`
/// of every commit and completion (core/commit_journal.h numbers the steps). After a SIGINT
/// the commit goes on for 300 ms first: the signal watcher must wait for the commit's end.
void InterruptCommitAt(int step, bool kill);

/// Arms InterruptCommitAt from `spec`, `<step>:<kill|int>`; returns false, and arms nothing,
/// when `spec` is null or not of that form.
bool InterruptCommitAsSpecified(const char* spec);

}  // namespace uwbsar::testing
