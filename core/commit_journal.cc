#include "core/commit_journal.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/errors.h"
#include "core/interrupt_cleanup.h"

namespace uwbsar {
namespace fs = std::filesystem;
namespace {

constexpr const char* kJournalHeader = "uwbsar-commit 1";
constexpr const char* kStagePrefix = ".uwbsar-partial-";

/// The test hook of the interruption tests (test/core/commit_journal_test.cc,
/// test/slam/session/session_safety_cli_test.cc): UWBSAR_TEST_INTERRUPT_COMMIT=<step>:<kill|int>
/// sends SIGKILL, or SIGINT, to this process at that step of a commit or completion (0: before
/// the journal, 1: after it, then after each removal and each rename, last after the journal
/// is gone). Unset in use. `step` counts the steps of one commit.
void CommitStep(int* step) {
  const char* hook = std::getenv("UWBSAR_TEST_INTERRUPT_COMMIT");
  const int now = (*step)++;
  int at = -1;
  char what[8] = {};
  if (hook == nullptr || std::sscanf(hook, "%d:%7s", &at, what) != 2 || now != at) return;
  if (std::strcmp(what, "kill") == 0) ::raise(SIGKILL);
  ::kill(::getpid(), SIGINT);
  // Give the signal watcher time to act while the commit goes on: it must wait for it.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
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

CommitPlan ReadJournal(const std::string& journal) {
  std::ifstream in(journal);
  if (!in) throw std::runtime_error(journal + ": cannot read the commit journal");
  CommitPlan plan;
  std::string line;
  int number = 0;
  bool ended = false;
  auto bad = [&](const std::string& what) -> InputError {
    return InputError(journal + " line " + std::to_string(number) + ": " + what +
                      " (not a commit journal uwbsar wrote; remove it to use the folder)");
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
    } else if (key == "remove") {
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
  const DeferInterrupts hold_signals;
  int step = 1;  // the journal is there
  Complete(dir, plan, &step);
  return true;
}

bool HasInterruptedCommit(const std::string& dir) {
  std::error_code ec;
  return fs::exists(fs::path(dir) / kCommitJournalName, ec);
}

}  // namespace uwbsar
