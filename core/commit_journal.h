// Publishing a set of files into a folder as one commit (docs/refusals.md, the
// session rule): a folder holds either the old complete result or the new complete one, never
// a mix, whatever kills the process and whenever.
//
// The files are first written into a staging folder inside the output folder. The commit
// point is the journal `DIR/.uwbsar-commit` (written to a temporary name, synced, renamed):
// it lists the staged files to publish and the earlier outputs to remove. Before it exists
// the old result is untouched (a staging folder left by a dead process is just removed);
// once it exists the commit is completed by whoever comes next: this process, or the next
// uwbsar command that locks the folder (RecoverInterruptedCommit). Completing is idempotent,
// so an interruption of the completion is completed again. The last published file (the
// marker, summary.json) is removed first and published last, so a folder whose completion
// is pending never looks complete.
#pragma once

#include <string>
#include <vector>

namespace uwbsar {

constexpr const char* kCommitJournalName = ".uwbsar-commit";

struct CommitPlan {
  std::string stage_name;            ///< the staging folder, a direct child of DIR
  std::vector<std::string> publish;  ///< staged names moved into DIR in order; the last is
                                     ///< the marker of a complete result
  std::vector<std::string> remove;   ///< earlier outputs in DIR this commit does not write
};

/// Commits `plan` into `dir` (held under an exclusive FolderLock by the caller): checks that
/// every name to publish is in the stage, syncs them, writes the journal, then completes it.
/// SIGINT/SIGTERM are held back from the journal to the end (DeferInterrupts). Throws
/// std::runtime_error naming the path on an I/O failure before the commit point (nothing in
/// DIR has changed then) and after it (the next command into DIR completes the commit).
void CommitFolder(const std::string& dir, const CommitPlan& plan);

/// Completes the commit whose journal is in `dir`, if there is one (the caller holds an
/// exclusive FolderLock). Returns whether there was one. Throws InputError naming the
/// journal's line when it is not one uwbsar wrote (a name with a path in it, an unknown line).
bool RecoverInterruptedCommit(const std::string& dir);

/// Whether `dir` holds the journal of an interrupted commit.
bool HasInterruptedCommit(const std::string& dir);

/// A step of a commit or of its completion, counted per commit: 0 before the journal, 1 after
/// it, then one after each removal and each rename, the last after the journal is gone.
using CommitStepObserver = void (*)(int step);

/// Calls `observer` at every step of every commit and completion from now on (nullptr: none,
/// the default). The seam through which the interruption tests kill a commit at a chosen step
/// (test/core/commit_interrupt.h); set it before any commit starts.
void SetCommitStepObserver(CommitStepObserver observer);

}  // namespace uwbsar
