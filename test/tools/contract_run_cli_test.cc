// The CLI contract (issue 29) on real runs: `demo` saves its session (so `--resume` extends
// it), one summary.json shape, localize's trajectory from the first fix, progress on every
// long command (UWBSAR_PROGRESS=1 draws it without a terminal), -v's per-stage log, every
// command lists what it wrote, a failed map leaves no folder it created, and the results.mcap
// of map, map --resume and localize read back with the Python mcap readers; localize prints
// its ATE, an emulated `run` its calibration once and no device folder. One demo and one
// simulated bag serve every test (seconds each).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "test/cli_runner.h"

namespace {

namespace fs = std::filesystem;
using uwbsar::testing::CliRun;
using uwbsar::testing::Uwbsar;

const std::string kMap = std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml";

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

nlohmann::json Json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

/// `uwbsar <args>` with UWBSAR_PROGRESS set to `progress`.
CliRun UwbsarWithProgress(const std::string& progress, const std::string& args) {
  return uwbsar::testing::RunCommand("UWBSAR_PROGRESS=" + progress + " " + std::string(UWBSAR_BIN) +
                                     " " + args);
}

class CliContractRunTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(
        (fs::temp_directory_path() / ("uwbsar_contract_run_" + std::to_string(::getpid())))
            .string());
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    demo_ = new CliRun(UwbsarWithProgress("1", "demo --out " + *dir_ + "/demo"));
    // The same room (scene seed 1, as the demo's), another drive: it revisits the demo's map.
    bag_ = new CliRun(UwbsarWithProgress(
        "1", "simulate --map " + kMap + " --seed 2 --scene-seed 1 --out " + *dir_ + "/bag2"));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete demo_;
    delete bag_;
  }
  void SetUp() override {
    ASSERT_EQ(demo_->exit_code, 0) << demo_->output;
    ASSERT_EQ(bag_->exit_code, 0) << bag_->output;
  }
  static std::string* dir_;
  static CliRun* demo_;
  static CliRun* bag_;
};
std::string* CliContractRunTest::dir_ = nullptr;
CliRun* CliContractRunTest::demo_ = nullptr;
CliRun* CliContractRunTest::bag_ = nullptr;

// README, docs/cli.md: demo writes every output of `map`; it wrote no session.uwbsar, so `--resume
// out/demo` failed. The summary of a plain map and of a resumed one have the same shape.
TEST_F(CliContractRunTest, DemoSavesItsSessionAndSummariesShareOneShape) {
  EXPECT_TRUE(fs::exists(*dir_ + "/demo/session.uwbsar"));
  EXPECT_TRUE(Has(demo_->output, "wrote " + *dir_ + "/demo: ")) << demo_->output;
  EXPECT_TRUE(Has(demo_->output, "session.uwbsar")) << demo_->output;
  const CliRun r =
      Uwbsar("map " + *dir_ + "/bag2 --resume " + *dir_ + "/demo --out " + *dir_ + "/resumed");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Has(r.output, "wrote " + *dir_ + "/resumed: ")) << r.output;
  EXPECT_FALSE(Has(r.output, "\r[")) << r.output;  // no terminal, no UWBSAR_PROGRESS: no bar
  const nlohmann::json plain = Json(*dir_ + "/demo/summary.json");
  const nlohmann::json joined = Json(*dir_ + "/resumed/summary.json");
  for (const nlohmann::json* s : {&plain, &joined}) {
    for (const char* key : {"input", "keyframes", "loops", "runs", "ate", "processing_s"}) {
      EXPECT_TRUE(s->contains(key)) << key << " in " << s->dump();
    }
    EXPECT_TRUE((*s)["loops"].contains("accepted")) << s->dump();
    EXPECT_TRUE((*s)["ate"].contains("rmse_m")) << s->dump();
    EXPECT_TRUE((*s)["ate"].contains("yaw_rmse_deg")) << s->dump();
    const nlohmann::json& last = (*s)["runs"].back();
    for (const char* key : {"id", "input", "keyframes", "tum", "ate"}) {
      EXPECT_TRUE(last.contains(key)) << key << " in " << last.dump();
    }
    EXPECT_EQ((*s)["ate"], last["ate"]) << s->dump();  // the newest run's ATE at the top
  }
  EXPECT_EQ(plain["runs"].size(), 1u);
  EXPECT_EQ(plain["runs"][0]["tum"], "trajectory.tum");
  EXPECT_EQ(joined["runs"].size(), 2u);
  EXPECT_EQ(joined["input"], *dir_ + "/bag2");
}

// trajectory.tum started at t = 0 (poses back-corrected from the first fix), not at the first
// fix as documented.
TEST_F(CliContractRunTest, LocalizeTrajectoryStartsAtTheFirstFix) {
  const std::string out = *dir_ + "/localized";
  const CliRun r = UwbsarWithProgress(
      "1", "localize " + *dir_ + "/bag2 --map " + *dir_ + "/demo --out " + out + " --verbose");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Has(r.output, "% of ")) << r.output;                                // progress
  EXPECT_TRUE(Has(r.output, "uwbsar: debug: stage localisation: ")) << r.output;  // -v
  EXPECT_TRUE(
      Has(r.output, "wrote " + out + ": trajectory.tum, localize.csv, results.mcap, summary.json"))
      << r.output;
  const nlohmann::json s = Json(out + "/summary.json");
  ASSERT_FALSE(s["first_fix"].is_null()) << s.dump();
  const double fix_s = s["first_fix"]["time_s"].get<double>();
  ASSERT_GT(fix_s, 1.0) << "the test needs a fix after the start";
  // The first odometry stamp of the bag: its ground truth starts with it (the simulator
  // writes both from the start of the run).
  std::ifstream truth(*dir_ + "/bag2/ground_truth.tum");
  std::string line;
  while (std::getline(truth, line) && line[0] == '#') {
  }
  const double start_s = std::stod(line);
  std::ifstream tum(out + "/trajectory.tum");
  ASSERT_TRUE(std::getline(tum, line));
  const double first_s = std::stod(line);
  EXPECT_GE(first_s, start_s + fix_s - 1e-6) << line;
  EXPECT_LT(first_s, start_s + fix_s + 0.1) << line;
}

// Only `map` drew progress; simulate, localize, detectors and merge were silent for seconds
// (demo, simulate: SetUp; localize: above). -v changed nothing; it prints the per-stage log.
TEST_F(CliContractRunTest, EveryLongCommandDrawsProgressAndVerboseLogsStages) {
  EXPECT_TRUE(Has(demo_->output, "\r[")) << demo_->output;
  EXPECT_TRUE(Has(demo_->output, "% of ")) << demo_->output;
  EXPECT_TRUE(Has(bag_->output, "% of ")) << bag_->output;
  EXPECT_TRUE(Has(bag_->output, "wrote ")) << bag_->output;
  const std::string d = *dir_;
  const std::string b = d + "/bag2";
  CliRun r = UwbsarWithProgress("1", "map -v " + b + " --out " + d + "/alone");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Has(r.output, "% of ")) << r.output;
  for (const char* stage :
       {"uwbsar: debug: stage imaging: ", "uwbsar: debug: stage features: ",
        "uwbsar: debug: stage matching: ", "uwbsar: debug: stage optimisation: ",
        "uwbsar: debug: stage outputs: "}) {
    EXPECT_TRUE(Has(r.output, stage)) << stage << " in " << r.output;
  }
  EXPECT_FALSE(Has(demo_->output, "debug")) << demo_->output;  // only with -v
  r = UwbsarWithProgress("1", "detectors " + b + " --no-images --out " + d + "/det");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Has(r.output, "% of the detector comparison")) << r.output;
  // A second independent session: the bag mapped on its own (above).
  r = UwbsarWithProgress("1", "merge -v " + d + "/demo " + d + "/alone --out " + d + "/merged");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Has(r.output, "% of the second session's keyframes matched")) << r.output;
  EXPECT_TRUE(Has(r.output, "uwbsar: debug: stage merge matching: ")) << r.output;
  EXPECT_TRUE(Has(r.output, "wrote " + d + "/merged: ")) << r.output;
  // -q: no bar even when forced.
  r = UwbsarWithProgress("1", "simulate -q --map " + kMap + " --route loop --out " + d + "/bag_q");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
}

// A failed map left an empty --out folder behind; one that existed before stays.
TEST(CliContractMapTest, FailedMapLeavesNoFolderItCreated) {
  const std::string dir =
      (fs::temp_directory_path() / ("uwbsar_contract_fail_" + std::to_string(::getpid()))).string();
  fs::remove_all(dir);
  fs::create_directories(dir + "/existing");
  std::ofstream(dir + "/empty.mcap") << "";
  for (const std::string& bag : {dir + "/none", dir + "/empty.mcap"}) {
    CliRun r = Uwbsar("map " + bag + " --out " + dir + "/new");
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_FALSE(fs::exists(dir + "/new")) << bag;
    r = Uwbsar("map " + bag + " --out " + dir + "/existing");
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_TRUE(fs::is_directory(dir + "/existing")) << bag;
  }
  fs::remove_all(dir);
}

// Foxglove / RViz users open results.mcap: checked with the independent Python `mcap` and
// `mcap-ros2-support` readers (test/tools/check_results_mcap.py): schemas, one /map per
// solve with the last equal to map.pgm, paths ending where the .tum files end, /tf in order.
TEST_F(CliContractRunTest, ResultsMcapOfMapResumeAndLocalizeReadBackInPython) {
  const char* venv = std::getenv("UWBSAR_VENV");
  if (venv == nullptr) GTEST_SKIP() << "UWBSAR_VENV is not set (make test sets it)";
  const std::string check =
      std::string(venv) + "/bin/python " + UWBSAR_SOURCE_DIR + "/test/tools/check_results_mcap.py ";
  const CliRun run = uwbsar::testing::RunCommand(check + "run " + *dir_ + "/demo");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  const CliRun resumed_map =
      Uwbsar("map " + *dir_ + "/bag2 --resume " + *dir_ + "/demo --out " + *dir_ + "/joined");
  ASSERT_EQ(resumed_map.exit_code, 0) << resumed_map.output;
  EXPECT_TRUE(Has(resumed_map.output, "results.mcap")) << resumed_map.output;
  const CliRun session = uwbsar::testing::RunCommand(check + "session " + *dir_ + "/joined");
  EXPECT_EQ(session.exit_code, 0) << session.output;
  const CliRun localized = Uwbsar("localize " + *dir_ + "/bag2 --map " + *dir_ + "/demo --out " +
                                  *dir_ + "/localized_mcap");
  ASSERT_EQ(localized.exit_code, 0) << localized.output;
  const CliRun localize =
      uwbsar::testing::RunCommand(check + "localize " + *dir_ + "/localized_mcap");
  EXPECT_EQ(localize.exit_code, 0) << localize.output;
  // slam.results_mcap: false leaves it out.
  const std::string no_mcap = *dir_ + "/no_mcap.yaml";
  std::ofstream(no_mcap) << "slam:\n  results_mcap: false\n";
  const CliRun off = Uwbsar("--config " + no_mcap + " localize " + *dir_ + "/bag2 --map " + *dir_ +
                            "/demo --out " + *dir_ + "/localized_plain");
  ASSERT_EQ(off.exit_code, 0) << off.output;
  EXPECT_FALSE(fs::exists(*dir_ + "/localized_plain/results.mcap"));
}

}  // namespace

namespace {

int Occurrences(const std::string& text, const std::string& part) {
  int n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) {
    ++n;
  }
  return n;
}

// README's `uwbsar run --emulate`: it printed the odometry-calibration line twice and left an
// empty <out>/dev, the folder of the emulated devices' links.
TEST(CliContractLiveTest, EmulatedRunPrintsTheCalibrationOnceAndLeavesNoDeviceFolder) {
  const std::string dir =
      (fs::temp_directory_path() / ("uwbsar_contract_live_" + std::to_string(::getpid()))).string();
  fs::remove_all(dir);
  const CliRun r = Uwbsar("run --emulate --speed 4 --duration 12 --out " + dir + "/live");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Has(r.output, "keyframes")) << r.output;  // a map's summary, with its calibration
  EXPECT_EQ(Occurrences(r.output, "odometry calibration: "), 1) << r.output;
  EXPECT_TRUE(fs::exists(dir + "/live/summary.json"));
  EXPECT_FALSE(fs::exists(dir + "/live/dev"));
  fs::remove_all(dir);
}

}  // namespace

namespace {

// `localize` wrote its ATE to summary.json only; `map` prints its own.
TEST_F(CliContractRunTest, LocalizePrintsItsAteWhenTheBagHasGroundTruth) {
  const std::string out = *dir_ + "/localized_ate";
  const CliRun r = Uwbsar("localize " + *dir_ + "/bag2 --map " + *dir_ + "/demo --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json s = Json(out + "/summary.json");
  ASSERT_TRUE(s.contains("ate")) << s.dump();
  char line[128];
  std::snprintf(line, sizeof line, "ATE RMSE %.2f cm (odometry alone %.2f cm) over %d poses",
                s["ate"]["rmse_m"].get<double>() * 100,
                s["odometry_ate"]["rmse_m"].get<double>() * 100, s["ate"]["poses"].get<int>());
  EXPECT_TRUE(Has(r.output, line)) << line << " in " << r.output;
}

}  // namespace
