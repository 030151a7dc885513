// A commit publishes a staged set of files as one: interrupted at any step (kill -9 through
// the test hook, in a child process), the folder holds the old complete set until the next
// command completes the journal, and then the new one; a SIGINT during the commit waits for it
// to end. The folder lock refuses a second process, naming the holder.
#include "core/commit_journal.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "core/errors.h"
#include "core/folder_lock.h"
#include "core/interrupt_cleanup.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;
using Files = std::map<std::string, std::string>;

const Files kOld = {
    {"a.txt", "old a"}, {"b.txt", "old b"}, {"old_only.txt", "x"}, {"summary.json", "old"}};
const Files kNew = {
    {"a.txt", "new a"}, {"b.txt", "new b"}, {"new_only.txt", "y"}, {"summary.json", "new"}};
constexpr const char* kStage = ".uwbsar-partial-1";

void WriteFiles(const fs::path& dir, const Files& files) {
  fs::create_directories(dir);
  for (const auto& [name, text] : files) std::ofstream(dir / name) << text;
}

/// The visible files of `dir` with their contents.
Files ReadFiles(const fs::path& dir) {
  Files files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name[0] == '.') continue;
    std::ifstream in(e.path());
    std::stringstream text;
    text << in.rdbuf();
    files[name] = text.str();
  }
  return files;
}

CommitPlan Plan() {
  CommitPlan plan;
  plan.stage_name = kStage;
  plan.publish = {"a.txt", "b.txt", "new_only.txt", "summary.json"};
  plan.remove = {"old_only.txt"};
  return plan;
}

fs::path FreshFolder(const std::string& tag) {
  const fs::path dir =
      fs::temp_directory_path() / ("uwbsar_commit_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  WriteFiles(dir, kOld);
  WriteFiles(dir / kStage, kNew);
  return dir;
}

/// Runs the commit in a child process with the hook set; returns its wait status.
int CommitInChild(const fs::path& dir, const std::string& hook, bool watch_signals) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setenv("UWBSAR_TEST_INTERRUPT_COMMIT", hook.c_str(), 1);
    if (watch_signals) InstallInterruptCleanup();
    const RemoveOnInterrupt guard((dir / kStage).string());
    try {
      CommitFolder(dir.string(), Plan());
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

TEST(CommitJournalTest, AKillAtAnyStepLeavesTheOldOrTheNewCompleteSet) {
  int interrupted = 0;
  for (int step = 0; step < 40; ++step) {
    const fs::path dir = FreshFolder("kill");
    const int status = CommitInChild(dir, std::to_string(step) + ":kill", false);
    if (WIFEXITED(status)) {  // past the last step: the commit ran through
      ASSERT_EQ(WEXITSTATUS(status), 0);
      EXPECT_EQ(ReadFiles(dir), kNew);
      fs::remove_all(dir);
      break;
    }
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "step " << step;
    ++interrupted;
    // Before anyone completes it: never a folder that looks complete with a mix in it.
    const Files now = ReadFiles(dir);
    if (now.count("summary.json") != 0) {
      EXPECT_TRUE(now == kOld || now == kNew) << "step " << step;
    }
    // The next command into the folder completes the journal, or there was none.
    const bool had_journal = RecoverInterruptedCommit(dir.string());
    EXPECT_EQ(had_journal, step >= 1 && step < 7) << "step " << step;  // 7: after the end
    EXPECT_EQ(ReadFiles(dir), step == 0 ? kOld : kNew) << "step " << step;
    EXPECT_FALSE(HasInterruptedCommit(dir.string()));
    EXPECT_EQ(fs::exists(dir / kStage), step == 0) << "step " << step;  // a dead run's stage
    fs::remove_all(dir);
  }
  // 0: before the journal, 1: after it, one removal, four renames, the end.
  EXPECT_EQ(interrupted, 8);
}

TEST(CommitJournalTest, ASigintDuringTheCommitWaitsForItsEnd) {
  for (int step = 0; step < 8; ++step) {
    const fs::path dir = FreshFolder("int");
    const int status = CommitInChild(dir, std::to_string(step) + ":int", true);
    // Before the commit point the signal ends the process at once; after it the commit ends
    // first (the process may even return before the watcher ends it).
    const bool by_signal = WIFSIGNALED(status) && WTERMSIG(status) == SIGINT;
    ASSERT_TRUE(by_signal || (step >= 1 && WIFEXITED(status) && WEXITSTATUS(status) == 0))
        << "step " << step;
    // No completion needed: before the journal the stage is dropped, after it the commit ends.
    EXPECT_EQ(ReadFiles(dir), step == 0 ? kOld : kNew) << "step " << step;
    EXPECT_FALSE(HasInterruptedCommit(dir.string())) << "step " << step;
    EXPECT_FALSE(fs::exists(dir / kStage)) << "step " << step;
    fs::remove_all(dir);
  }
}

TEST(CommitJournalTest, AJournalNotWrittenByUwbsarIsRefusedNamingItsLine) {
  const fs::path dir = FreshFolder("hostile");
  std::ofstream(dir / kCommitJournalName)
      << "uwbsar-commit 1\nstage .uwbsar-partial-1\npublish ../../etc/passwd\nend\n";
  try {
    RecoverInterruptedCommit(dir.string());
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(".uwbsar-commit line 3"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ReadFiles(dir), kOld);
  fs::remove_all(dir);
}

/// Tries to lock `dir` in a child process: 0 when granted, 3 when refused (the message goes
/// to `message`).
int LockInChild(const fs::path& dir, FolderLock::Mode mode, std::string* message) {
  int fds[2];
  if (::pipe(fds) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    try {
      const FolderLock lock(dir.string(), mode);
      ::_exit(0);
    } catch (const InputError& e) {
      const std::string text = e.what();
      if (::write(fds[1], text.data(), text.size()) < 0) ::_exit(4);
      ::_exit(3);
    }
  }
  ::close(fds[1]);
  char buf[512];
  message->clear();
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) message->append(buf, n);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(FolderLockTest, ASecondProcessIsRefusedNamingTheHolder) {
  const fs::path dir = FreshFolder("lock");
  std::string message;
  {
    const FolderLock lock(dir.string(), FolderLock::Mode::kExclusive);
    const FolderLock again(dir.string(), FolderLock::Mode::kShared);  // same process: granted
    EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kShared, &message), 3);
    EXPECT_NE(message.find("in use by another uwbsar process (pid " + std::to_string(::getpid())),
              std::string::npos)
        << message;
    EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kExclusive, &message), 3);
  }
  {
    const FolderLock reader(dir.string(), FolderLock::Mode::kShared);
    EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kShared, &message), 0);  // readers share
    EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kExclusive, &message), 3);
    {
      const FolderLock writer(dir.string(), FolderLock::Mode::kExclusive);  // upgraded
      EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kShared, &message), 3);
    }
    EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kShared, &message), 0);  // back to shared
  }
  EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kExclusive, &message), 0);  // all released
  fs::remove_all(dir);
}

}  // namespace
}  // namespace uwbsar
