// A saved map is never lost (docs/refusals.md, the session rule), tried as a
// careless user would: a resume that does not connect, a kill -9 or Ctrl-C at every step of
// the commit, a second process on the same folder, localising into a map's folder, the same
// recording joined twice, a plain run into a map's folder. After each, the saved map is
// byte-identical unless a join the user asked for completed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "core/commit_journal.h"
#include "core/folder_lock.h"
#include "test/cli_runner.h"
#include "test/core/commit_interrupt.h"
#include "test/slam/session/session_cli_fixture.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;
using testing::Json;
using testing::Lines;
using testing::RunCommand;
using testing::SessionCliTest;
using testing::Uwbsar;
using Files = std::map<std::string, std::string>;

/// The files of `dir` (not its lock file) with their bytes.
Files ReadFiles(const std::string& dir) {
  Files files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == kFolderLockName || e.is_directory()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    files[name] = bytes.str();
  }
  return files;
}

std::string CopyOf(const std::string& from, const std::string& to) {
  fs::remove_all(to);
  fs::copy(from, to, fs::copy_options::recursive);
  return to;
}

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(SessionCliTest, AResumeThatNeverConnectsIsRefusedAndTheMapIsUnchanged) {
  const std::string out = CopyOf(Map("a"), *dir_ + "/no_connect");
  const Files before = ReadFiles(out);
  const CliRun r = Uwbsar("map " + Bag("c") + " --resume " + out + " --out " + out);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r.output, "does not connect to the saved map")) << r.output;
  EXPECT_EQ(Lines(r.output), 1) << r.output;
  EXPECT_EQ(ReadFiles(out), before);
}

TEST_F(SessionCliTest, AnInterruptedJoinLeavesTheSavedMapOrTheWholeJoinedOne) {
  const std::string join = "--config " + *dir_ + "/b.yaml -q map " + Bag("b") + " --resume ";
  const std::string reference = CopyOf(Map("a"), *dir_ + "/join_ref");
  ASSERT_EQ(Uwbsar(join + reference + " --out " + reference).exit_code, 0);
  const Files joined = ReadFiles(reference), saved = ReadFiles(Map("a"));
  ASSERT_NE(joined.at("session.uwbsar"), saved.at("session.uwbsar"));
  int interrupted = 0;
  for (const char* signal : {"kill", "int"}) {
    for (int step = 0; step < 40; ++step) {
      const std::string out = CopyOf(Map("a"), *dir_ + "/join_" + signal);
      // The tests' build of uwbsar, whose commit this variable interrupts at `step`.
      const CliRun r =
          RunCommand(std::string(testing::kInterruptCommitVariable) + "=" + std::to_string(step) +
                     ":" + signal + " " + UWBSAR_HOOKS_BIN + " " + join + out + " --out " + out);
      if (r.exit_code == 0) break;  // past the commit's last step
      // Ended by the signal (the shell reports 128 + SIGKILL or SIGINT, or the signal itself).
      ASSERT_TRUE(r.exit_code == -1 || r.exit_code == 137 || r.exit_code == 130)
          << signal << " at step " << step << ": exit " << r.exit_code << " " << r.output;
      ++interrupted;
      {  // what the next command into the folder does first
        const FolderLock lock(out, FolderLock::Mode::kExclusive);
        RecoverInterruptedCommit(out);
      }
      const Files now = ReadFiles(out);
      if (now == saved) continue;  // the saved map, byte for byte
      // Otherwise the whole joined map: the same files, the same session bytes, two runs.
      EXPECT_EQ(now.at("session.uwbsar"), joined.at("session.uwbsar"))
          << signal << " at step " << step;
      ASSERT_EQ(now.size(), joined.size()) << signal << " at step " << step;
      for (const auto& [name, bytes] : joined) EXPECT_EQ(now.count(name), 1u) << name;
      EXPECT_EQ(Json(out + "/summary.json")["runs"].size(), 2u);
      // Trying again cannot join the same recording twice.
      const CliRun again = Uwbsar(join + out + " --out " + out);
      EXPECT_EQ(again.exit_code, 3) << again.output;
      EXPECT_TRUE(Has(again.output, "already in")) << again.output;
    }
  }
  std::printf("the join interrupted at %d steps of its commit (kill -9 and SIGINT)\n", interrupted);
  EXPECT_GE(interrupted, 2 * 10);  // before and after the journal, 3 removals, 11 renames, end
}

TEST_F(SessionCliTest, ASecondProcessOnTheSameFolderIsRefusedNamingTheFirst) {
  const std::string out = *dir_ + "/busy";
  fs::create_directories(out);
  {
    const FolderLock held(out, FolderLock::Mode::kExclusive);
    const CliRun r = Uwbsar("map " + Bag("a") + " --out " + out);
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_TRUE(
        Has(r.output, "in use by another uwbsar process (pid " + std::to_string(::getpid())))
        << r.output;
    EXPECT_EQ(Lines(r.output), 1) << r.output;
  }
  // Two real processes: the second starts once the first holds the folder (its pid is in
  // the lock file: the first's, not the test's of a moment ago).
  const std::string bin = UWBSAR_BIN;
  const std::string wait_for_first =
      "n=0; while ! grep -q \"pid $pid:\" " + out +
      "/.uwbsar.lock && [ $n -lt 600 ]; do sleep 0.05; n=$((n+1)); done; ";  // at most 30 s
  const CliRun r = RunCommand(bin + " -q map " + Bag("a") + " --out " + out + " & pid=$!; " +
                              wait_for_first + bin + " -q map " + Bag("b") + " --out " + out +
                              "; echo second=$?; wait $pid; echo first=$?");
  EXPECT_TRUE(Has(r.output, "second=3")) << r.output;
  EXPECT_TRUE(Has(r.output, "first=0")) << r.output;
  EXPECT_EQ(Json(out + "/summary.json")["input"], Bag("a"));
}

TEST_F(SessionCliTest, LocalizeNeverWritesIntoAMapsFolder) {
  const std::string out = CopyOf(Map("a"), *dir_ + "/loc_in_map");
  const Files before = ReadFiles(out);
  for (const std::string& map : {out, Map("a")}) {
    const CliRun r = Uwbsar("localize " + Bag("b") + " --map " + map + " --out " + out);
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_TRUE(Has(r.output, "localisation never writes into a map's folder")) << r.output;
    EXPECT_EQ(Lines(r.output), 1) << r.output;
  }
  // The live path: refused before any emulated device or recording is made in the folder.
  const CliRun live = Uwbsar("run --emulate --localize-in " + out + " --out " + out);
  EXPECT_EQ(live.exit_code, 3) << live.output;
  EXPECT_TRUE(Has(live.output, "localisation never writes into a map's folder")) << live.output;
  EXPECT_EQ(ReadFiles(out), before);
  EXPECT_FALSE(fs::exists(out + "/dev"));
}

TEST_F(SessionCliTest, TheSameRecordingIsNeverJoinedTwice) {
  const CliRun self =
      Uwbsar("map " + Bag("a") + " --resume " + Map("a") + " --out " + *dir_ + "/twice_a");
  EXPECT_EQ(self.exit_code, 3) << self.output;
  EXPECT_TRUE(Has(self.output, "already in " + Map("a") + "/session.uwbsar as run 0"))
      << self.output;
  const CliRun same =
      Uwbsar("merge " + Map("a") + " " + Map("a") + "/session.uwbsar --out " + *dir_ + "/twice_m");
  EXPECT_EQ(same.exit_code, 3) << same.output;
  EXPECT_TRUE(Has(same.output, "the same session")) << same.output;
  const std::string ab = *dir_ + "/twice_ab";
  ASSERT_EQ(Uwbsar("--config " + *dir_ + "/b.yaml -q map " + Bag("b") + " --resume " + Map("a") +
                   " --out " + ab)
                .exit_code,
            0);
  const CliRun contained = Uwbsar("merge " + Map("a") + " " + ab + " --out " + *dir_ + "/m_aab");
  EXPECT_EQ(contained.exit_code, 3) << contained.output;
  EXPECT_TRUE(Has(contained.output, "already in")) << contained.output;
  EXPECT_FALSE(fs::exists(*dir_ + "/m_aab/summary.json"));
  for (const std::string& name : {std::string("twice_a"), std::string("twice_m")}) {
    EXPECT_FALSE(fs::exists(*dir_ + "/" + name + "/summary.json")) << name;
  }
}

TEST_F(SessionCliTest, APlainRunReplacesASavedMapOnlyWithOverwrite) {
  const std::string out = CopyOf(Map("a"), *dir_ + "/replace");
  const Files before = ReadFiles(out);
  const CliRun r = Uwbsar("map " + Bag("b") + " --out " + out);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r.output, "holds a saved map")) << r.output;
  EXPECT_EQ(ReadFiles(out), before);
  const CliRun o = Uwbsar("-q map " + Bag("b") + " --out " + out + " --overwrite");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(Json(out + "/summary.json")["input"], Bag("b"));
}

TEST_F(SessionCliTest, AMapBeyondItsPixelBudgetIsRefusedBeforeAllocation) {
  std::ofstream(*dir_ + "/tiny_budget.yaml") << "limits:\n  max_image_pixels: 1.0e+4\n";
  const std::string out = *dir_ + "/over_budget";
  const CliRun r =
      Uwbsar("--config " + *dir_ + "/tiny_budget.yaml map " + Bag("a") + " --out " + out);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r.output, Bag("a") + ": the map of its keyframes is ")) << r.output;
  EXPECT_TRUE(Has(r.output, "more than limits.max_image_pixels (10000)")) << r.output;
  EXPECT_FALSE(fs::exists(out + "/summary.json"));
}

TEST_F(SessionCliTest, AnOutputThatIsAFolderIsFoundBeforeTheWork) {
  const std::string out = *dir_ + "/session_folder";
  fs::create_directories(out + "/session.uwbsar");
  const CliRun r = Uwbsar("map " + Bag("a") + " --out " + out);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r.output, "session.uwbsar: output file is a folder")) << r.output;
  EXPECT_EQ(Lines(r.output), 1) << r.output;
  EXPECT_FALSE(fs::exists(out + "/map.png"));
}

}  // namespace
}  // namespace uwbsar
