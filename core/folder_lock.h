// One writer per folder (docs/refusals.md, the session rule): a command that
// writes an output folder holds an exclusive lock on it for its whole run, and a command that
// reads a saved session holds a shared lock on the session's folder, so that no second process
// can write a folder being written or read. The lock is flock(2) on `DIR/.uwbsar.lock`: the
// kernel releases it when the process ends however it ends (kill -9 included), so a lock is
// never stale. The file also names the holders (pid, command line, start time; a writer, or
// the readers) for the refusal. It is opened without following links and never truncated
// before the lock is held: a lock file that is a link could point at a saved map.
#pragma once

#include <memory>
#include <string>

namespace uwbsar {

/// The name of the lock file inside a locked folder. It is never removed (removing a lock
/// file races with a process that is opening it).
constexpr const char* kFolderLockName = ".uwbsar.lock";

class FolderLock {
 public:
  enum class Mode { kShared, kExclusive };

  /// Locks `dir` (which must exist) in `mode` without waiting. Throws InputError (one line,
  /// exit 3) naming `dir` and the process that holds it when another process holds a
  /// conflicting lock. Within one process the locks on a folder are shared: a second lock on
  /// a folder this process holds exclusively is granted, and a shared lock is upgraded in place
  /// when an exclusive one is asked for. A lock file that is not a regular file (a link, even
  /// to nothing, a FIFO, a folder) or that cannot be opened is refused naming it (InputError),
  /// but for a reader on read-only media: it locks through an existing lock file or, on a
  /// read-only file system without one, not at all (nothing can write the folder then).
  FolderLock(const std::string& dir, Mode mode);
  ~FolderLock();
  FolderLock(FolderLock&&) noexcept;
  FolderLock& operator=(FolderLock&&) noexcept;
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  std::string key_;  ///< the canonical path (the registry's key); "" when moved from
};

}  // namespace uwbsar
