// What `uwbsar` refuses (docs/refusals.md): global options after the
// subcommand, YAML of the wrong shape, out-of-range values, outputs that cannot be written,
// failures that leave nothing behind, and -q that quiets every command.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test/cli_runner.h"

namespace {

namespace fs = std::filesystem;
using uwbsar::testing::CliRun;
using uwbsar::testing::Uwbsar;

std::string TempDir(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("uwbsar_refuse_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

void WriteFile(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/// The bundled room (our own map): these tests need a map, not the paper's room.
const std::string kMap = std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml";

// README: `uwbsar run --config config/robot.yaml --emulate` (rule 11). Every subcommand takes
// --config after its name, and a bad configuration is refused before any work (exit 3).
TEST(CliRefusalTest, ConfigIsAcceptedAfterEverySubcommand) {
  const std::string dir = TempDir("config_after");
  const std::string bad = dir + "/bad.yaml";
  WriteFile(bad, "imaging:\n  pixle_size_m: 0.01\n");
  const std::string any_file = bad;  // satisfies ExistingFile checks of required arguments
  for (const std::string& command : std::vector<std::string>{
           "config", "image --synthetic straight --out " + dir + "/o", "demo --out " + dir + "/o",
           "optimize " + any_file, "loops --from-stats " + any_file, "detectors " + dir,
           "map " + dir + " --out " + dir + "/o", "info " + dir, "check " + dir,
           "simulate --map " + any_file + " --out " + dir + "/b",
           "compare " + any_file + " " + any_file + " --out " + dir + "/o",
           "export-pcd " + any_file + " --out " + dir + "/o.pcd", "run --emulate"}) {
    const CliRun r = Uwbsar(command + " --config " + bad);
    EXPECT_EQ(r.exit_code, 3) << command << ": " << r.output;
    EXPECT_NE(r.output.find("bad.yaml:2: unknown key 'imaging.pixle_size_m'"), std::string::npos)
        << command << ": " << r.output;
  }
  // And a good one is used: -q and -v work after the subcommand too.
  WriteFile(dir + "/good.yaml", "imaging:\n  pixel_size_m: 0.004\n");
  const CliRun r = Uwbsar("config --config " + dir + "/good.yaml -q");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("pixel_size_m: 0.004"), std::string::npos) << r.output;
}

// Rule 12: a scalar where a mapping belongs, or a complex key: exit 3 naming file and line.
TEST(CliRefusalTest, YamlOfTheWrongShapeIsBadInputNamingFileAndLine) {
  const std::string dir = TempDir("shape");
  WriteFile(dir + "/complex.yaml", "imaging:\n  ? [a, b]\n  : 1\n");
  CliRun r = Uwbsar("config --config " + dir + "/complex.yaml");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("complex.yaml:2"), std::string::npos) << r.output;
  fs::create_directories(dir + "/bag");
  WriteFile(dir + "/bag/metadata.yaml",
            "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
            "  duration: 5\n  starting_time:\n    nanoseconds_since_epoch: 1\n"
            "  message_count: 0\n  relative_file_paths: [bag_0.db3]\n");
  r = Uwbsar("info " + dir + "/bag");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("metadata.yaml:4: field 'duration'"), std::string::npos) << r.output;
}

// Rule 14: values that used to be accepted silently.
TEST(CliRefusalTest, OutOfRangeValuesAreRefused) {
  const std::string dir = TempDir("values");
  for (const char* seed : {"-1", "18446744073709551616", "1e3", "0x10"}) {
    const CliRun r = Uwbsar("simulate --map " + kMap + " --out " + dir + "/b --seed " + seed);
    EXPECT_EQ(r.exit_code, 2) << seed << ": " << r.output;
    EXPECT_NE(r.output.find("--seed"), std::string::npos) << r.output;
  }
  EXPECT_EQ(Uwbsar("demo --out " + dir + "/d --seed -1").exit_code, 2);
  for (const char* duration : {"-5", "nan", "0", "inf"}) {
    const CliRun r =
        Uwbsar(std::string("run --emulate --out ") + dir + "/r --duration " + duration);
    EXPECT_EQ(r.exit_code, 2) << duration << ": " << r.output;
  }
  EXPECT_EQ(Uwbsar("run --emulate --out " + dir + "/r --speed nan").exit_code, 2);
  // A text-log record with trailing fields is malformed (docs/formats.md: text logs).
  WriteFile(dir + "/run.log", "odom 100 0 0 0\nodom 200 0.1 0 0 extra\n");
  const CliRun r = Uwbsar("image --log " + dir + "/run.log --out " + dir + "/img");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("run.log:2: unexpected 'extra'"), std::string::npos) << r.output;
}

// Rule 14: a solve that fails writes nothing that would look like a result.
TEST(CliRefusalTest, OptimizeWritesNothingAfterAFailedSolve) {
  const std::string dir = TempDir("optimize");
  const std::string chain =
      "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1e300 0 0\nVERTEX_SE2 2 2 0 0\n"
      "EDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\nEDGE_SE2 1 2 1 0 0 1 0 0 1 0 1\n";
  WriteFile(dir + "/inf_cost.g2o", chain);                                          // "converges"
  WriteFile(dir + "/no_converge.g2o", chain + "EDGE_SE2 0 2 2 0 0 1 0 0 1 0 1\n");  // fails
  for (const char* name : {"inf_cost", "no_converge"}) {
    const CliRun r = Uwbsar("optimize " + dir + "/" + name + ".g2o --out " + dir +
                            "/out.g2o --tum " + dir + "/out.tum --png " + dir + "/out.png");
    EXPECT_EQ(r.exit_code, 1) << name << ": " << r.output;
    EXPECT_NE(r.output.find("no output written"), std::string::npos) << name << ": " << r.output;
    EXPECT_FALSE(fs::exists(dir + "/out.g2o")) << name;
    EXPECT_FALSE(fs::exists(dir + "/out.tum")) << name;
    EXPECT_FALSE(fs::exists(dir + "/out.png")) << name;
  }
}

// Rule 14: -q leaves only errors.
TEST(CliRefusalTest, QuietQuietsEveryCommand) {
  const std::string dir = TempDir("quiet");
  CliRun r = Uwbsar("simulate -q --map " + kMap + " --route loop --out " + dir + "/bag");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
  r = Uwbsar("compare " + kMap + " " + kMap + " --align origin --out " + dir + "/cmp -q");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
  r = Uwbsar("export-pcd " + kMap + " --out " + dir + "/m.pcd -q");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
  r = Uwbsar("image --synthetic straight --out " + dir + "/img -q");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
}

// Rules 13 and 15: every output path is checked before the work, and the same failure has
// the same exit code (3) and message in every command.
TEST(CliRefusalTest, UnwritableOutputIsRefusedBeforeTheWorkWithOneExitCode) {
  const std::string dir = TempDir("outputs");
  WriteFile(dir + "/graph.g2o",
            "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\n"
            "EDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n");
  WriteFile(dir + "/file", "x");
  fs::create_directories(dir + "/folder");
  struct Case {
    std::string command, message;
  } cases[] = {
      {"optimize " + dir + "/graph.g2o --out " + dir + "/folder", "output file is a folder"},
      {"export-pcd " + kMap + " --out " + dir + "/folder", "output file is a folder"},
      {"image --synthetic straight --out " + dir + "/file", "output folder is a file"},
      {"detectors " + dir + "/folder --out " + dir + "/file", "output folder is a file"},
      {"compare " + kMap + " " + kMap + " --out " + dir + "/file", "output folder is a file"},
      {"demo --out " + dir + "/file", "output folder is a file"},
      {"simulate --map " + kMap + " --out " + dir + "/file/bag", "is a file"},
      {"simulate --map " + kMap + " --out " + dir + "/b --text-log " + dir + "/folder",
       "output file is a folder"},
  };
  for (const Case& c : cases) {
    const CliRun r = Uwbsar(c.command);
    EXPECT_EQ(r.exit_code, 3) << c.command << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.command << ": " << r.output;
    // Refused before the work: nothing of the work was printed.
    EXPECT_EQ(r.output.find("wrote"), std::string::npos) << c.command << ": " << r.output;
  }
  EXPECT_FALSE(fs::exists(dir + "/b"));
  EXPECT_FALSE(fs::exists(dir + "/b.partial"));
}

// Rule 13: a simulation that runs out of space names the path and the cause, exits 1 like
// every I/O failure, and leaves no BAG.partial that would block the retry. (The file size
// limit stands in for a full disk: hermetic and needs no mount.)
TEST(CliRefusalTest, FailedSimulateCleansItsPartialAndNamesTheCause) {
  const std::string dir = TempDir("full");
  const CliRun r =
      uwbsar::testing::RunCommand("trap '' XFSZ; ulimit -f 512; " + std::string(UWBSAR_BIN) +
                                  " simulate --map " + kMap + " --out " + dir + "/bag");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(dir + "/bag.partial/bag_0.db3"), std::string::npos) << r.output;
  // (On a full disk the cause reads "no space left on device"; checked by hand on a 2 MB
  // tmpfs, which a test cannot mount without privileges.)
  EXPECT_EQ(r.output.find("no transaction is active"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/bag.partial"));
  EXPECT_FALSE(fs::exists(dir + "/bag"));
  const CliRun retry = Uwbsar("simulate -q --map " + kMap + " --out " + dir + "/bag");
  EXPECT_EQ(retry.exit_code, 0) << retry.output;
}

// Rule 15: `info` on a bag whose metadata starts at the last representable instant and
// still claims a duration: refused naming the field, never an end in 1677 (signed overflow).
TEST(CliRefusalTest, InfoRefusesTimesThatWouldOverflow) {
  const std::string dir = TempDir("int64");
  const CliRun sim = Uwbsar("simulate -q --map " + kMap + " --out " + dir + "/bag");
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  std::ifstream in(dir + "/bag/metadata.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::string key = "nanoseconds_since_epoch: ";
  for (std::size_t at = 0; (at = text.find(key, at)) != std::string::npos;) {
    at += key.size();
    text.replace(at, text.find('\n', at) - at, "9223372036854775807");
  }
  std::ofstream(dir + "/bag/metadata.yaml", std::ios::trunc) << text;
  const CliRun r = Uwbsar("info " + dir + "/bag");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("metadata.yaml:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("field 'duration': starting_time + duration is past"), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("1677"), std::string::npos) << r.output;
}

}  // namespace
