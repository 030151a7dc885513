// Inputs and outputs kept apart (docs/refusals.md), as a careless user meets them: an output
// on top of an input, an input that is a device or a FIFO, a saved session read in WAL mode or
// found damaged, an empty output path. After each refusal the inputs are byte-identical
// (sha256) and nothing was created. Runs on a 1 m simulated bag mapped once per process.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/stat.h>

#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "test/cli_runner.h"
#include "test/slam/session/sqlite_edit.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;
using testing::LineCount;
using testing::RunCommand;

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string Sha256(const std::string& path) {
  const CliRun r = RunCommand("sha256sum " + path, /*merge_stderr=*/false);
  return r.exit_code == 0 ? r.output.substr(0, 64) : "unreadable";
}

/// The names in `dir`, hidden ones (the lock file, -wal, -shm, staging folders) included.
std::set<std::string> Listing(const std::string& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

class InputsOutputsCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(testing::FreshFolder("uwbsar_inputs_outputs", "suite"));
    testing::WriteTextFile(Config(), "simulator:\n  route:\n    depart_distance_m: 1.0\n");
    const std::string hall =
        std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml";
    CliRun r = Uwbsar("simulate --map " + hall + " --out " + Bag());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = Uwbsar("map " + Bag() + " --out " + Map());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    dir_ = nullptr;
  }
  /// `uwbsar -q --config <the 1 m route> <args>`.
  static CliRun Uwbsar(const std::string& args) {
    return testing::Uwbsar("-q --config " + Config() + " " + args);
  }
  static std::string Config() { return *dir_ + "/short.yaml"; }
  static std::string Bag() { return *dir_ + "/bag"; }
  static std::string Map() { return *dir_ + "/map"; }
  static std::string CopyOf(const std::string& from, const std::string& name) {
    const std::string to = *dir_ + "/" + name;
    fs::remove_all(to);
    fs::copy(from, to, fs::copy_options::recursive);
    return to;
  }
  static std::string* dir_;
};
std::string* InputsOutputsCliTest::dir_ = nullptr;

// Item 3: `map BAG --out BAG` replaced the recording's ground_truth.tum, `localize BAG ...
// --out BAG` deleted it.
TEST_F(InputsOutputsCliTest, AnOutputOnOrInsideAnInputIsRefusedNamingBoth) {
  const std::string bag = Bag(), truth = Bag() + "/ground_truth.tum";
  const std::string own_truth = *dir_ + "/truth.tum";
  fs::copy_file(truth, own_truth, fs::copy_options::overwrite_existing);
  const std::string renamed = *dir_ + "/renamed";  // a session file not named session.uwbsar
  fs::create_directories(renamed);
  fs::copy_file(Map() + "/session.uwbsar", renamed + "/other.uwbsar",
                fs::copy_options::overwrite_existing);
  const std::string before = Sha256(truth);
  const std::set<std::string> listing = Listing(bag);
  fs::create_directory_symlink(bag, *dir_ + "/bag_link");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"map " + bag + " --out " + bag, "--out " + bag + " is the input bag " + bag},
      {"map " + bag + " --out " + bag + "/sub", "--out " + bag + "/sub lies inside the input bag"},
      {"localize " + bag + " --map " + Map() + " --out " + bag, "is the input bag " + bag},
      {"map " + *dir_ + "/bag_link --out " + bag + "/", "is the input bag " + *dir_ + "/bag_link"},
      {"calibrate " + bag + " --out " + truth, "lies inside the input bag " + bag},
      {"calibrate " + bag + " --out " + Config(), "is the --config file " + Config()},
      {"map " + bag + " --ground-truth " + own_truth + " --out " + own_truth,
       "is the --ground-truth file " + own_truth},
      {"localize " + bag + " --map " + renamed + "/other.uwbsar --out " + renamed,
       "--out " + renamed + " is the --map session " + renamed},
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = Uwbsar(args);
    EXPECT_EQ(r.exit_code, 3) << args << ": " << r.output;
    EXPECT_TRUE(Has(r.output, message)) << args << ": " << r.output;
    EXPECT_EQ(LineCount(r.output), 1) << args << ": " << r.output;
  }
  EXPECT_EQ(Sha256(truth), before);
  EXPECT_EQ(Sha256(own_truth), before);
  EXPECT_EQ(Listing(bag), listing);
  EXPECT_EQ(Listing(renamed), std::set<std::string>{"other.uwbsar"});
  // The --resume session's own folder is its output by design: not refused by this rule (this
  // bag is in the map already, which is refused instead).
  const CliRun own = Uwbsar("map " + bag + " --resume " + Map() + " --out " + Map());
  EXPECT_EQ(own.exit_code, 3) << own.output;
  EXPECT_TRUE(Has(own.output, "already in")) << own.output;
}

// Item 10: `--ground-truth /dev/zero` read 14.6 GB in 40 s, a FIFO hung. Each command runs
// capped (3 GB, 60 s), so that a regression fails instead of exhausting the machine.
TEST_F(InputsOutputsCliTest, EveryInputThatIsNotARegularFileIsRefusedByName) {
  const std::string fifo = *dir_ + "/fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string fifo_bag = CopyOf(Bag(), "fifo_bag");
  fs::remove(fifo_bag + "/bag_0.db3");
  ASSERT_EQ(::mkfifo((fifo_bag + "/bag_0.db3").c_str(), 0600), 0);
  testing::WriteTextFile(*dir_ + "/tiny_budget.yaml", "limits:\n  max_input_file_mb: 0.001\n");
  const std::string out = *dir_ + "/not_created";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"map " + Bag() + " --ground-truth /dev/zero --out " + out,
       "/dev/zero: trajectory file is not a regular file (a device)"},
      {"map " + Bag() + " --ground-truth " + fifo + " --out " + out,
       fifo + ": trajectory file is not a regular file (a FIFO)"},
      {"calibrate " + Bag() + " --ground-truth " + fifo, "trajectory file is not a regular file"},
      {"optimize " + fifo, fifo + ": g2o file is not a regular file (a FIFO)"},
      {"loops --from-stats " + fifo, fifo + ": statistics file is not a regular file (a FIFO)"},
      {"info " + fifo, fifo + ": bag file is not a regular file (a FIFO)"},
      {"info " + fifo_bag, "bag_0.db3: bag storage file is not a regular file (a FIFO)"},
      {"simulate --map " + std::string(UWBSAR_SOURCE_DIR) +
           "/config/maps/seed_hall/seed_hall.yaml --route " + fifo + " --out " + out,
       fifo + ": waypoints file is not a regular file (a FIFO)"},
      {"--config " + *dir_ + "/tiny_budget.yaml map " + Bag() + " --ground-truth " + Bag() +
           "/ground_truth.tum --out " + out,
       "ground_truth.tum: trajectory file is larger than limits.max_input_file_mb (1048 bytes)"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = RunCommand("ulimit -v 3000000; timeout 60 " + std::string(UWBSAR_BIN) +
                                " -q --config " + Config() + " " + args);
    EXPECT_EQ(r.exit_code, 3) << args << ": " << r.output;
    EXPECT_TRUE(Has(r.output, message)) << args << ": " << r.output;
    EXPECT_EQ(LineCount(r.output), 1) << args << ": " << r.output;
  }
  EXPECT_FALSE(fs::exists(out));
}

// Item 11: reading a session in WAL mode left -wal and -shm files in the map's folder. Every
// reader (localize, merge, map --resume) now leaves the folder as it was; changes only a -wal
// holds are refused, not read past or folded in.
TEST_F(InputsOutputsCliTest, ASessionInWalModeIsReadWithoutChangingItsFolder) {
  const std::string map = CopyOf(Map(), "wal_map"), copy = CopyOf(Map(), "wal_copy");
  const std::string session = map + "/session.uwbsar";
  testing::RunSql(session, "PRAGMA journal_mode=WAL");
  const std::set<std::string> listing = Listing(map);
  const std::string before = Sha256(session);
  ASSERT_EQ(listing.count("session.uwbsar-wal") + listing.count("session.uwbsar-shm"), 0u);
  const CliRun localized =
      Uwbsar("localize " + Bag() + " --map " + map + " --out " + *dir_ + "/wal_localized");
  EXPECT_EQ(localized.exit_code, 0) << localized.output;
  EXPECT_EQ(Listing(map), listing);
  for (const std::string& args :  // both read the session before refusing the same run twice
       {"merge " + map + " " + copy + " --out " + *dir_ + "/wal_merged",
        "map " + Bag() + " --resume " + map + " --out " + *dir_ + "/wal_resumed"}) {
    const CliRun r = Uwbsar(args);
    EXPECT_EQ(r.exit_code, 3) << args << ": " << r.output;
    EXPECT_TRUE(Has(r.output, "already in")) << args << ": " << r.output;
    EXPECT_EQ(Listing(map), listing) << args;
  }
  EXPECT_EQ(Sha256(session), before);
  // A change still in the -wal (its writer has not checkpointed it) is refused by name.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(session.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db,
                         "PRAGMA wal_autocheckpoint=0; INSERT INTO meta(key, value) "
                         "VALUES('note', 'pending')",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  const std::set<std::string> pending = Listing(map);
  const std::string wal = Sha256(session + "-wal");
  const CliRun r =
      Uwbsar("localize " + Bag() + " --map " + map + " --out " + *dir_ + "/wal_pending");
  EXPECT_EQ(Sha256(session + "-wal"), wal);
  sqlite3_close(db);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r.output, session + "-wal holds changes not yet in the session")) << r.output;
  EXPECT_EQ(LineCount(r.output), 1) << r.output;
  EXPECT_FALSE(fs::exists(*dir_ + "/wal_pending"));
  EXPECT_EQ(pending.count("session.uwbsar-wal"), 1u);
}

// Item 11: a refused `localize` on a damaged session created its --out folder holding a lock
// file. Nothing is created before the inputs are accepted.
TEST_F(InputsOutputsCliTest, ALocalizeRefusedForADamagedSessionCreatesNothing) {
  const std::string damaged = CopyOf(Map(), "damaged");
  fs::resize_file(damaged + "/session.uwbsar", fs::file_size(damaged + "/session.uwbsar") / 2);
  const std::string out = *dir_ + "/damaged_localized";
  const CliRun r = Uwbsar("localize " + Bag() + " --map " + damaged + " --out " + out);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r.output, damaged + "/session.uwbsar")) << r.output;
  EXPECT_EQ(LineCount(r.output), 1) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// Item 14: `--out ''` said ": cannot create output folder".
TEST_F(InputsOutputsCliTest, AnEmptyOutputPathIsNamed) {
  const std::string any = Config();  // an existing file where a command needs one
  for (const std::string& command :
       {"map " + Bag(), "localize " + Bag() + " --map " + Map(), "merge " + Map() + " " + Map(),
        std::string("demo"), std::string("run --emulate"), "simulate --map " + any,
        std::string("image --synthetic straight"), "detectors " + Bag(), "calibrate " + Bag(),
        "compare " + any + " " + any, "export-pcd " + any, "loops --images " + *dir_,
        "match " + any + " " + any, "optimize " + any}) {
    const CliRun r = Uwbsar(command + " --out ''");
    EXPECT_EQ(r.exit_code, 3) << command << ": " << r.output;
    EXPECT_EQ(r.output, "uwbsar: error: --out: empty path\n") << command;
  }
}

}  // namespace
}  // namespace uwbsar
