// A commit publishes a staged set of files as one: interrupted at any step (kill -9 through
// the journal's step seam, test/core/commit_interrupt.h, in a child process), the folder holds the
// old complete set until the next command completes the journal, and then the new one; a SIGINT
// during the commit waits for it to end. A journal that does not match its stage, or names uwbsar's
// own files, is refused and nothing in the folder moves.
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
#include "core/interrupt_cleanup.h"
#include "test/core/commit_interrupt.h"

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

/// Runs the commit in a child process that interrupts itself at `step` (SIGKILL if `kill`,
/// else SIGINT); returns its wait status.
int CommitInChild(const fs::path& dir, int step, bool kill, bool watch_signals) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    testing::InterruptCommitAt(step, kill);
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
    const int status = CommitInChild(dir, step, /*kill=*/true, false);
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
    const int status = CommitInChild(dir, step, /*kill=*/false, true);
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

/// The journal uwbsar would write for `plan`, with `extra` lines before its end.
std::string JournalText(const CommitPlan& plan, const std::string& extra = "") {
  std::string text = "uwbsar-commit 1\nstage " + plan.stage_name + "\n";
  for (const std::string& name : plan.remove) text += "remove " + name + "\n";
  for (const std::string& name : plan.publish) text += "publish " + name + "\n";
  return text + extra + "end\n";
}

/// Completing `dir`'s journal is refused naming the journal and `what`, and nothing moves.
void ExpectJournalRefused(const fs::path& dir, const std::string& what) {
  const Files before = ReadFiles(dir);
  try {
    RecoverInterruptedCommit(dir.string());
    ADD_FAILURE() << "accepted: " << what;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((dir / kCommitJournalName).string()), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_EQ(ReadFiles(dir), before) << what;
  EXPECT_TRUE(fs::exists(fs::symlink_status(dir / kCommitJournalName))) << what;
}

TEST(CommitJournalTest, AJournalThatDoesNotMatchItsStageIsRefusedAndNothingMoves) {
  const fs::path dir = FreshFolder("mismatch");
  const fs::path other = dir.string() + "_other";  // another folder's files
  WriteFiles(other, kNew);
  std::ofstream(dir / kCommitJournalName) << JournalText(Plan());
  const fs::path stage = dir / kStage;
  fs::remove_all(stage);  // a user who cleans up hidden folders
  ExpectJournalRefused(dir, "stage .uwbsar-partial-1 is missing");
  fs::create_directory_symlink(other, stage);
  ExpectJournalRefused(dir, "stage .uwbsar-partial-1 is a symbolic link");
  fs::remove(stage);
  WriteFiles(stage, kNew);
  fs::remove(stage / "b.txt");
  fs::create_symlink(other / "b.txt", stage / "b.txt");
  ExpectJournalRefused(dir, "b.txt");
  fs::remove(stage / "b.txt");  // neither staged nor published
  ExpectJournalRefused(dir, "b.txt");
  WriteFiles(stage, kNew);
  fs::remove(dir / kCommitJournalName);  // the journal itself not a regular file
  fs::create_directory(dir / kCommitJournalName);
  ExpectJournalRefused(dir, "not a regular file");
  fs::remove(dir / kCommitJournalName);
  std::ofstream(other / "journal") << JournalText(Plan());
  fs::create_symlink(other / "journal", dir / kCommitJournalName);
  ExpectJournalRefused(dir, "not a regular file");
  EXPECT_EQ(ReadFiles(other).at("b.txt"), kNew.at("b.txt"));
  fs::remove(dir / kCommitJournalName);  // a sound journal still completes
  std::ofstream(dir / kCommitJournalName) << JournalText(Plan());
  EXPECT_TRUE(RecoverInterruptedCommit(dir.string()));
  EXPECT_EQ(ReadFiles(dir), kNew);
  fs::remove_all(dir);
  fs::remove_all(other);
}

TEST(CommitJournalTest, AJournalNamingUwbsarsOwnFilesIsRefused) {
  const fs::path dir = FreshFolder("own");
  std::ofstream(dir / ".uwbsar.lock") << "the lock\n";
  std::ofstream(dir / kStage / ".uwbsar.lock") << "not the lock\n";
  for (const std::string line : {"publish .uwbsar.lock", "remove .uwbsar.lock",
                                 "publish .uwbsar-commit", "remove .uwbsar-partial-1"}) {
    std::ofstream(dir / kCommitJournalName) << JournalText(Plan(), line + "\n");
    ExpectJournalRefused(dir, ".uwbsar-commit line 8");
    std::ifstream lock(dir / ".uwbsar.lock");
    std::string text;
    std::getline(lock, text);
    EXPECT_EQ(text, "the lock") << line;
    EXPECT_TRUE(fs::is_directory(dir / kStage)) << line;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace uwbsar
