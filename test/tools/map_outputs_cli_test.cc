// What `uwbsar map` promises about its output folder:
// everything is staged and summary.json committed last, a committed folder holds one run's
// files, staging folders of dead processes are cleaned and Ctrl-C cleans its own, the
// output folder and the ground truth are checked before the work, and the summary's
// durations come from the data actually used.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "test/cli_runner.h"
#include "test/tools/map_test_bag.h"

extern char** environ;

namespace uwbsar {
namespace {

namespace fs = std::filesystem;
using map_test::BagEdits;
using map_test::TempDir;
using map_test::WriteRunBag;
using testing::CliRun;
using testing::Uwbsar;

/// Files and folders of `dir` (names only).
std::vector<std::string> Entries(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

bool HasStagingFolder(const std::string& dir) {
  for (const std::string& name : Entries(dir)) {
    if (name.rfind(".uwbsar-partial-", 0) == 0) return true;
  }
  return false;
}

/// The bag's ground truth as a TUM file: the odometry of the bag is the truth here.
std::string WriteGroundTruth(const std::string& dir) {
  const std::string path = dir + "/gt.tum";
  std::ofstream out(path);
  out.precision(17);
  for (int i = 0; i <= 80; ++i) {
    out << 1700000000.0 + 0.1 * i << " " << 0.05 * i << " 0 0 0 0 0 1\n";
  }
  return path;
}

TEST(MapOutputsTest, EveryOptionalOutputIsCommittedBeforeTheSummary) {
  const std::string dir = TempDir("exact_order");
  const std::string bag = WriteRunBag(dir, {});
  const CliRun r = Uwbsar("map " + bag + " --out " + dir + "/out --exact -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // summary.json is the last file written: no output is newer than it.
  const auto summary_time = fs::last_write_time(dir + "/out/summary.json");
  for (const char* f :
       {"map_exact.png", "map_exact_float.tif", "map_exact_grid.yaml", "map.png", "report.html"}) {
    ASSERT_TRUE(fs::exists(dir + "/out/" + f)) << f;
    EXPECT_LE(fs::last_write_time(dir + "/out/" + f), summary_time) << f << " after the summary";
  }
}

TEST(MapOutputsTest, CommittedFolderHoldsExactlyOneRunsFiles) {
  const std::string dir = TempDir("one_run");
  const std::string bag = WriteRunBag(dir, {});
  const std::string out = dir + "/out";
  const CliRun first = Uwbsar("map " + bag + " --out " + out + " --exact --ground-truth " +
                              WriteGroundTruth(dir) + " -q");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  ASSERT_TRUE(fs::exists(out + "/ground_truth.tum"));
  ASSERT_TRUE(fs::exists(out + "/map_exact.png"));
  std::ofstream(out + "/notes.txt") << "not ours\n";
  // The first run's saved map is replaced only when asked to.
  const CliRun second = Uwbsar("map " + bag + " --out " + out + " -q --overwrite");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  // The second run wrote neither ground truth nor an exact map: none of the first's stays.
  for (const char* f :
       {"ground_truth.tum", "map_exact.png", "map_exact_float.tif", "map_exact_grid.yaml"}) {
    EXPECT_FALSE(fs::exists(out + "/" + f)) << f << " of the previous run is still there";
  }
  EXPECT_TRUE(fs::exists(out + "/notes.txt")) << "a file that is not an output was removed";
  std::ifstream summary_file(out + "/summary.json");
  EXPECT_FALSE(nlohmann::json::parse(summary_file).contains("ate"));
}

TEST(MapOutputsTest, StaleStagingFoldersOfDeadProcessesAreRemoved) {
  const std::string dir = TempDir("stale");
  const std::string bag = WriteRunBag(dir, {});
  const std::string out = dir + "/out";
  // A pid that is certainly gone: a child that has exited and been reaped.
  const pid_t dead = fork();
  if (dead == 0) _exit(0);
  waitpid(dead, nullptr, 0);
  const std::string stale = out + "/.uwbsar-partial-" + std::to_string(dead);
  const std::string alive = out + "/.uwbsar-partial-" + std::to_string(getpid());
  fs::create_directories(stale);
  fs::create_directories(alive);
  std::ofstream(stale + "/map.png") << "x";
  const CliRun r = Uwbsar("map " + bag + " --out " + out + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(stale)) << "the staging folder of a dead process stayed";
  EXPECT_TRUE(fs::exists(alive)) << "the staging folder of a live process was removed";
}

TEST(MapOutputsTest, CtrlCRemovesItsOwnStagingFolder) {
  const std::string dir = TempDir("sigint");
  const std::string bag = WriteRunBag(dir, {true, true, 0.0, 12.0});
  const std::string out = dir + "/out";
  fs::create_directories(out);
  std::vector<std::string> args = {UWBSAR_BIN, "map", bag, "--out", out, "-q"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, UWBSAR_BIN, nullptr, nullptr, argv.data(), environ), 0);
  // The staging folder exists from the start of the work (it proves the folder writable).
  const std::string stage = out + "/.uwbsar-partial-" + std::to_string(pid);
  bool seen = false;
  for (int i = 0; i < 2000 && !seen; ++i) {
    seen = fs::exists(stage);
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(seen) << "no staging folder appeared";
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    GTEST_SKIP() << "the run finished before the signal arrived";
  }
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_FALSE(HasStagingFolder(out)) << "Ctrl-C left the staging folder";
  EXPECT_FALSE(fs::exists(out + "/summary.json"));
}

TEST(MapOutputsTest, OutputFolderAndGroundTruthAreCheckedBeforeTheWork) {
  const std::string dir = TempDir("late_checks");
  const std::string bag = WriteRunBag(dir, {});
  // An output "folder" that is a file: exit 3 naming it, as for every command.
  std::ofstream(dir + "/file") << "x";
  CliRun r = Uwbsar("map " + bag + " --out " + dir + "/file");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find(dir + "/file: output folder is a file"), std::string::npos) << r.output;
  // A malformed ground truth is named before anything is mapped or created.
  std::ofstream(dir + "/bad.tum") << "1 2 3\n";
  r = Uwbsar("map " + bag + " --out " + dir + "/out --ground-truth " + dir + "/bad.tum");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find(dir + "/bad.tum:1"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/out")) << "the work started before the ground truth was read";
}

TEST(MapOutputsTest, DurationsComeFromTheDataActuallyUsed) {
  // One odometry message stamped 1 ns before a 2023 run of 8 s: the log is not 53 years long.
  const std::string dir = TempDir("stray_stamp");
  BagEdits edits;
  edits.stray_odometry_at_1ns = true;
  const std::string bag = WriteRunBag(dir, edits);
  const CliRun r = Uwbsar("map " + bag + " --out " + dir + "/out");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream summary_file(dir + "/out/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  const double duration = summary["log_duration_s"].get<double>();
  std::printf("log_duration_s %.3f, real_time_factor %.1f\n", duration,
              summary["real_time_factor"].get<double>());
  EXPECT_GT(duration, 4.0);
  EXPECT_LT(duration, 9.0);
}

}  // namespace
}  // namespace uwbsar
