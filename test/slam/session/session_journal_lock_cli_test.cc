// A map folder that is not as uwbsar left it (docs/refusals.md, "A saved map is never lost"):
// a commit journal that does not match its stage (the stage removed by a user who cleans up
// hidden folders, a stage that is a link to another map, a journal that is a FIFO), and a lock
// file that is a link (to the session, to a file outside the folder, to nothing). Each is
// refused with one line naming the file, and every saved map keeps its bytes (sha256).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "core/commit_journal.h"
#include "core/folder_lock.h"
#include "test/cli_runner.h"
#include "test/slam/session/session_cli_fixture.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;
using testing::CopyOf;
using testing::Lines;
using testing::RunCommand;
using testing::SessionCliTest;
using testing::Uwbsar;
using testing::WriteTextFile;

std::string Sha256(const std::string& path) {
  return RunCommand("sha256sum " + path, false).output.substr(0, 64);
}

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// A refusal: exit 3, one line naming `name`.
void ExpectRefusedNaming(const CliRun& r, const std::string& name) {
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r.output, name)) << r.output;
  EXPECT_EQ(Lines(r.output), 1) << r.output;
}

TEST_F(SessionCliTest, AJournalThatDoesNotMatchItsStageIsRefusedAndEveryMapKept) {
  const std::string journal_text_head = "uwbsar-commit 1\nstage .uwbsar-partial-1\n";
  const std::string localize = "localize " + Bag("b") + " --map ";
  // The stage is gone (a user cleaned up hidden folders): the journal still says what to remove.
  const std::string no_stage = CopyOf(Map("a"), *dir_ + "/journal_no_stage");
  const std::string saved = Sha256(no_stage + "/session.uwbsar");
  WriteTextFile(no_stage + "/" + kCommitJournalName,
                journal_text_head + "remove session.uwbsar\npublish summary.json\nend\n");
  ExpectRefusedNaming(Uwbsar(localize + no_stage + " --out " + *dir_ + "/journal_out_1"),
                      no_stage + "/" + kCommitJournalName);
  EXPECT_EQ(Sha256(no_stage + "/session.uwbsar"), saved);
  EXPECT_TRUE(fs::exists(no_stage + "/" + kCommitJournalName));  // left in place

  // The stage is a link to another map's folder: neither map changes.
  const std::string linked = CopyOf(Map("a"), *dir_ + "/journal_linked");
  const std::string other = CopyOf(Map("c"), *dir_ + "/journal_other");
  const std::string other_saved = Sha256(other + "/session.uwbsar");
  fs::create_directory_symlink(other, linked + "/.uwbsar-partial-1");
  WriteTextFile(linked + "/" + kCommitJournalName,
                journal_text_head + "publish session.uwbsar\npublish summary.json\nend\n");
  ExpectRefusedNaming(Uwbsar(localize + linked + " --out " + *dir_ + "/journal_out_2"),
                      linked + "/" + kCommitJournalName);
  EXPECT_EQ(Sha256(linked + "/session.uwbsar"), saved);
  EXPECT_EQ(Sha256(other + "/session.uwbsar"), other_saved);
  EXPECT_TRUE(fs::exists(other + "/summary.json"));

  // A journal that is a FIFO is refused without reading it (no hang: `timeout` ends one).
  const std::string fifo = CopyOf(Map("a"), *dir_ + "/journal_fifo");
  ASSERT_EQ(::mkfifo((fifo + "/" + kCommitJournalName).c_str(), 0644), 0);
  const CliRun r = RunCommand("timeout 20 " + std::string(UWBSAR_BIN) + " " + localize + fifo +
                              " --out " + *dir_ + "/journal_out_3");
  ExpectRefusedNaming(r, fifo + "/" + kCommitJournalName);
  EXPECT_EQ(Sha256(fifo + "/session.uwbsar"), saved);
}

TEST_F(SessionCliTest, ALockFileThatIsALinkIsRefusedAndNothingItPointsAtChanges) {
  const std::string lock = std::string("/") + kFolderLockName;
  const std::string saved = Sha256(Map("a") + "/session.uwbsar");
  // A link to the folder's own session: a join into the folder, and a plain map refused anyway.
  const std::string self = CopyOf(Map("a"), *dir_ + "/lock_to_session");
  fs::remove(self + lock);
  fs::create_symlink("session.uwbsar", self + lock);
  const std::string join = "--config " + *dir_ + "/b.yaml -q map " + Bag("b") + " --resume ";
  ExpectRefusedNaming(Uwbsar(join + self + " --out " + self), self + lock);
  EXPECT_EQ(Sha256(self + "/session.uwbsar"), saved);
  ExpectRefusedNaming(Uwbsar("-q map " + Bag("a") + " --out " + self), self + lock);
  EXPECT_EQ(Sha256(self + "/session.uwbsar"), saved);

  // A link to a file outside the folder: that file keeps its bytes.
  const std::string outside = *dir_ + "/outside.txt";
  WriteTextFile(outside, "not uwbsar's\n");
  const std::string outside_sum = Sha256(outside);
  const std::string out = *dir_ + "/lock_outside";
  fs::create_directories(out);
  fs::create_symlink(outside, out + lock);
  ExpectRefusedNaming(Uwbsar("-q map " + Bag("a") + " --out " + out), out + lock);
  EXPECT_EQ(Sha256(outside), outside_sum);

  // A link to nothing: two joins into one folder cannot both take a lock that is not there.
  const std::string dangling = CopyOf(Map("a"), *dir_ + "/lock_dangling");
  fs::remove(dangling + lock);
  fs::create_symlink(*dir_ + "/no_such_file", dangling + lock);
  ExpectRefusedNaming(Uwbsar(join + dangling + " --out " + dangling), dangling + lock);
  EXPECT_EQ(Sha256(dangling + "/session.uwbsar"), saved);
  EXPECT_FALSE(fs::exists(*dir_ + "/no_such_file"));
}

}  // namespace
}  // namespace uwbsar
