#include "core/commit_journal.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "core/errors.h"
#include "core/interrupt_cleanup.h"
#include "core/plain_file.h"

namespace uwbsar {
namespace fs = std::filesystem;
namespace {

constexpr const char* kJournalHeader = "uwbsar-commit 1";
constexpr const char* kStagePrefix = ".uwbsar-partial-";
constexpr std::size_t kMaxJournalBytes = 64 << 10;  // uwbsar's are a few hundred bytes
constexpr const char* kRemoveIt =
    " (not a commit journal uwbsar wrote; remove it to use the folder)";

std::atomic<CommitStepObserver> step_observer{nullptr};

/// Step `*step` of one commit, shown to the observer if there is one (SetCommitStepObserver).
void CommitStep(int* step) {
  const int now = (*step)++;
  if (const CommitStepObserver observer = step_observer.load()) observer(now);
}

[[noreturn]] void Fail(const std::string& path, const std::string& what, int error) {
  throw std::runtime_error(path + ": " + what + ": " + std::strerror(error));
}

void SyncPath(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) Fail(path, "cannot open to sync", errno);
  const int result = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  // Some file systems cannot sync a folder (EINVAL); the rename order still holds there.
  if (result != 0 && !(directory && error == EINVAL)) Fail(path, "cannot sync", error);
}

/// Writes the journal to a temporary name, syncs it and renames it into place: the commit.
void WriteJournal(const std::string& dir, const CommitPlan& plan) {
  std::ostringstream text;
  text << kJournalHeader << "\nstage " << plan.stage_name << "\n";
  for (const std::string& name : plan.remove) text << "remove " << name << "\n";
  for (const std::string& name : plan.publish) text << "publish " << name << "\n";
  text << "end\n";
  const std::string journal = dir + "/" + kCommitJournalName;
  const std::string tmp = journal + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) Fail(tmp, "cannot write the commit journal", errno);
  const std::string bytes = text.str();
  const bool written =
      ::write(fd, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
  const int error = written ? 0 : (errno != 0 ? errno : ENOSPC);
  if (!written || ::fsync(fd) != 0 || ::close(fd) != 0) {
    ::unlink(tmp.c_str());
    Fail(tmp, "cannot write the commit journal", error != 0 ? error : errno);
  }
  if (::rename(tmp.c_str(), journal.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp.c_str());
    Fail(journal, "cannot write the commit journal", e);
  }
  SyncPath(dir, true);
}

bool IsPlainName(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
         name.find('\0') == std::string::npos;
}

/// The journal's bytes: a regular file, neither followed through a link nor waited on (a FIFO).
std::string ReadJournalText(const std::string& journal) {
  std::string why;
  int error = 0;
  const int fd = OpenRegularFile(journal, O_RDONLY, &why, &error);
  if (fd < 0) throw InputError(journal + ": " + why + kRemoveIt);
  std::string text(kMaxJournalBytes + 1, '\0');
  std::size_t size = 0;
  for (ssize_t n; size < text.size() && (n = ::read(fd, &text[size], text.size() - size)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      error = errno;
      ::close(fd);
      throw InputError(journal + ": cannot read the commit journal: " + std::strerror(error));
    }
    size += static_cast<std::size_t>(n);
  }
  ::close(fd);
  if (size > kMaxJournalBytes) throw InputError(journal + ": larger than 64 KiB" + kRemoveIt);
  text.resize(size);
  return text;
}

/// A name of uwbsar's own (the lock file, the journal, a stage), which no commit publishes or
/// removes.
bool IsUwbsarsOwnName(const std::string& name) { return name.rfind(".uwbsar", 0) == 0; }

CommitPlan ReadJournal(const std::string& journal) {
  std::istringstream in(ReadJournalText(journal));
  CommitPlan plan;
  std::string line;
  int number = 0;
  bool ended = false;
  auto bad = [&](const std::string& what) -> InputError {
    return InputError(journal + " line " + std::to_string(number) + ": " + what + kRemoveIt);
  };
  while (std::getline(in, line)) {
    ++number;
    if (number == 1) {
      if (line != kJournalHeader) throw bad("unknown header '" + line + "'");
      continue;
    }
    if (line == "end") {
      ended = true;
      break;
    }
    const std::size_t space = line.find(' ');
    const std::string key = line.substr(0, space);
    const std::string name = space == std::string::npos ? "" : line.substr(space + 1);
    if (!IsPlainName(name)) throw bad("'" + name + "' is not a file name inside the folder");
    if (key == "stage" && name.rfind(kStagePrefix, 0) == 0) {
      plan.stage_name = name;
      continue;
    }
    if (IsUwbsarsOwnName(name)) throw bad("'" + name + "' is uwbsar's own file, not an output");
    if (key == "remove") {
      plan.remove.push_back(name);
    } else if (key == "publish") {
      plan.publish.push_back(name);
    } else {
      throw bad("unexpected line '" + line + "'");
    }
  }
  if (!ended || plan.stage_name.empty() || plan.publish.empty()) {
    throw bad("incomplete journal");
  }
  return plan;
}

/// What `path` is without following a link, and its mode (0 unless lstat says); "" when it is
/// not there.
std::string KindAt(const fs::path& path, mode_t* mode) {
  struct stat st {};
  *mode = 0;
  if (::lstat(path.c_str(), &st) != 0) {
    return errno == ENOENT ? "" : std::string("unreadable (") + std::strerror(errno) + ")";
  }
  *mode = st.st_mode;
  return FileKindName(st.st_mode);
}

/// Refuses a journal that does not match the folder as an interrupted commit leaves it: its
/// stage a folder of DIR's own (not a link), every file to publish a regular file in it or,
/// published before an interruption of the completion (in order: only names before the first
/// one still staged), in DIR; nothing to replace or remove a folder.
void CheckJournalMatchesFolder(const std::string& journal, const fs::path& out,
                               const CommitPlan& plan) {
  const auto refuse = [&](const std::string& what) {
    return InputError(journal + ": " + what +
                      "; not completed, nothing moved (remove it to use the folder)");
  };
  const fs::path stage = out / plan.stage_name;
  mode_t mode = 0;
  const std::string stage_kind = KindAt(stage, &mode);
  if (stage_kind.empty()) throw refuse("its stage " + plan.stage_name + " is missing");
  if (!S_ISDIR(mode)) throw refuse("its stage " + plan.stage_name + " is " + stage_kind);
  bool staged_seen = false;
  for (const std::string& name : plan.publish) {
    const std::string staged = KindAt(stage / name, &mode);
    if (!staged.empty() && !S_ISREG(mode)) {
      throw refuse("'" + name + "' in its stage is " + staged + ", not a regular file");
    }
    const bool in_stage = !staged.empty();
    staged_seen = staged_seen || in_stage;
    const std::string there = KindAt(out / name, &mode);
    if (in_stage && !there.empty() && S_ISDIR(mode)) {
      throw refuse("'" + name + "' would replace a folder");
    }
    if (!in_stage && (staged_seen || there.empty() || !S_ISREG(mode))) {
      throw refuse("'" + name + "' is not in its stage");
    }
  }
  for (const std::string& name : plan.remove) {
    if (!KindAt(out / name, &mode).empty() && S_ISDIR(mode)) {
      throw refuse("'" + name + "' to remove is a folder");
    }
  }
}

void RemoveIfThere(const fs::path& path) {
  if (::unlink(path.c_str()) != 0 && errno != ENOENT) Fail(path.string(), "cannot remove", errno);
}

/// Completes `plan` (idempotent, so an interrupted completion is completed again).
void Complete(const std::string& dir, const CommitPlan& plan, int* step) {
  const fs::path out(dir), stage = out / plan.stage_name;
  const std::string& marker = plan.publish.back();
  std::error_code ec;
  if (fs::exists(stage / marker, ec)) RemoveIfThere(out / marker);  // no old marker meanwhile
  for (const std::string& name : plan.remove) {
    RemoveIfThere(out / name);
    CommitStep(step);
  }
  for (const std::string& name : plan.publish) {
    if (!fs::exists(stage / name, ec)) continue;  // published before an interruption
    if (::rename((stage / name).c_str(), (out / name).c_str()) != 0) {
      Fail((out / name).string(), "cannot commit", errno);
    }
    CommitStep(step);
  }
  SyncPath(dir, true);
  RemoveIfThere(out / kCommitJournalName);
  fs::remove_all(stage, ec);
  CommitStep(step);
}

}  // namespace

void CommitFolder(const std::string& dir, const CommitPlan& plan) {
  if (plan.publish.empty() || !IsPlainName(plan.stage_name)) {
    throw std::logic_error("CommitFolder: nothing to publish or a bad stage name");
  }
  const fs::path stage = fs::path(dir) / plan.stage_name;
  for (const std::string& name : plan.publish) {
    if (!IsPlainName(name)) throw std::logic_error("CommitFolder: bad name " + name);
    SyncPath((stage / name).string(), false);  // also proves every staged file is there
  }
  SyncPath(stage.string(), true);
  int step = 0;
  CommitStep(&step);
  const DeferInterrupts hold_signals;  // from the commit point to a complete folder
  WriteJournal(dir, plan);
  CommitStep(&step);
  Complete(dir, plan, &step);
}

bool RecoverInterruptedCommit(const std::string& dir) {
  const std::string journal = dir + "/" + kCommitJournalName;
  if (!HasInterruptedCommit(dir)) return false;
  const CommitPlan plan = ReadJournal(journal);
  CheckJournalMatchesFolder(journal, dir, plan);
  const DeferInterrupts hold_signals;
  int step = 1;  // the journal is there
  Complete(dir, plan, &step);
  return true;
}

bool HasInterruptedCommit(const std::string& dir) {
  struct stat st {};  // whatever is there, a link to nothing or a FIFO included
  return ::lstat((fs::path(dir) / kCommitJournalName).c_str(), &st) == 0;
}

void SetCommitStepObserver(CommitStepObserver observer) { step_observer.store(observer); }

}  // namespace uwbsar
