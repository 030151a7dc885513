// The CLI contract (issue 29): exit 0 only for a usable result, every missing input file
// exit 3, one error style, --version, repeated --config merged, numbers printed shortest.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "test/cli_runner.h"
#include "test/shared_data.h"

namespace {

namespace fs = std::filesystem;
using uwbsar::testing::CliRun;
using uwbsar::testing::Uwbsar;

std::string TempDir(const std::string& name) {
  return uwbsar::testing::FreshFolder("uwbsar_contract", name);
}

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const std::string kMap = std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml";

// MIT-B with the defaults held back 11 of its 20 loops as unsupported and wrote the tangled
// graph with exit 0: now exit 1, one line naming the key, nothing written.
TEST(CliContractTest, OptimizeRefusesADegenerateSolutionNamingTheKey) {
  UWBSAR_NEED_SHARED_DATA("posegraph/input_MITb_g2o.g2o");
  const std::string dir = TempDir("optimize");
  const std::string mitb = uwbsar::testing::SharedDataPath("posegraph/input_MITb_g2o.g2o");
  CliRun r = Uwbsar("optimize -q " + mitb + " --out " + dir + "/out.g2o");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
  EXPECT_TRUE(Has(r.output, "uwbsar: error: 11 of 20 loops rejected")) << r.output;
  EXPECT_TRUE(Has(r.output, "backend.min_loop_support: 0")) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/out.g2o"));
  // The key it names gives a usable result.
  uwbsar::testing::WriteTextFile(dir + "/isolated.yaml", "backend:\n  min_loop_support: 0\n");
  r = Uwbsar("--config " + dir + "/isolated.yaml optimize -q " + mitb + " --init chordal --out " +
             dir + "/out.g2o");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir + "/out.g2o"));
}

// A log recorded with another radar (1152 samples a scan, the configuration says 1000):
// nothing imaged, refused with one line that names the key to change.
TEST(CliContractTest, ImageOfALogThatDoesNotFitNamesTheKey) {
  const std::string dir = TempDir("image");
  uwbsar::testing::WriteTextFile(dir + "/run.log", uwbsar::testing::TinyTextLog(1152));
  const CliRun r = Uwbsar("image --log " + dir + "/run.log --out " + dir + "/out", false);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  const CliRun e = Uwbsar("image -q --log " + dir + "/run.log --out " + dir + "/out");
  EXPECT_EQ(uwbsar::testing::LineCount(e.output), 1) << e.output;
  EXPECT_TRUE(Has(e.output, "none of the 25 scans could be imaged")) << e.output;
  EXPECT_TRUE(Has(e.output, "radars[].num_samples")) << e.output;
  EXPECT_FALSE(fs::exists(dir + "/out/strip_float.tif"));
}

// A missing --config or --ground-truth file was exit 2 while a missing bag was 3.
TEST(CliContractTest, EveryMissingInputFileIsExit3) {
  const std::string dir = TempDir("missing");
  const std::string none = dir + "/none";
  for (const std::string& args :
       {"--config " + none + " config", "map " + none + " --out " + dir + "/o",
        "map " + none + ".bag --out " + dir + "/o --ground-truth " + none + ".tum",
        "calibrate " + none, "calibrate " + dir + " --ground-truth " + none + ".tum",
        "image --log " + none + ".log --out " + dir + "/o", "optimize " + none + ".g2o",
        "loops --from-stats " + none + ".csv", "loops --images " + none,
        "match " + none + ".png " + none + "2.png", "detectors " + none, "info " + none,
        "simulate --map " + none + ".yaml --out " + dir + "/b",
        "simulate --map " + kMap + " --targets " + none + ".yaml --out " + dir + "/b",
        "demo --map " + none + ".yaml --out " + dir + "/d",
        "compare " + none + ".yaml " + kMap + " --out " + dir + "/c",
        "export-pcd " + none + ".yaml --out " + dir + "/m.pcd",
        "localize " + none + " --map " + none + "2 --out " + dir + "/l",
        "merge " + none + " " + none + "2 --out " + dir + "/m"}) {
    const CliRun r = Uwbsar(args);
    EXPECT_EQ(r.exit_code, 3) << args << ": " << r.output;
    EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << args << ": " << r.output;
    EXPECT_TRUE(Has(r.output, "uwbsar: error: ")) << args << ": " << r.output;
    EXPECT_TRUE(Has(r.output, none)) << args << ": " << r.output;
  }
}

// Two styles before: CLI11's "<what>\nRun with --help ..." and "uwbsar: error: <what>".
TEST(CliContractTest, OneErrorStyleAndUnknownSubcommandNamed) {
  CliRun r = Uwbsar("frobnicate");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output, "uwbsar: error: unknown subcommand 'frobnicate' (see uwbsar --help)\n");
  r = Uwbsar("-q --config x.yaml frobnicate --out x");
  EXPECT_EQ(r.exit_code, 3) << r.output;  // the missing --config is met first
  r = Uwbsar("image --no-such-flag");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
  EXPECT_EQ(r.output.rfind("uwbsar: error: ", 0), 0u) << r.output;
  EXPECT_TRUE(Has(r.output, "--no-such-flag")) << r.output;
  r = Uwbsar("");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output.rfind("uwbsar: error: ", 0), 0u) << r.output;
  r = Uwbsar("demo --seed -1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
  EXPECT_EQ(r.output.rfind("uwbsar: error: ", 0), 0u) << r.output;
}

TEST(CliContractTest, VersionFromTheProject) {
  const CliRun r = Uwbsar("--version");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, std::string("uwbsar ") + UWBSAR_VERSION + "\n");
}

// A robot's configuration and a calibration file from `uwbsar calibrate`: merged in order,
// the later file's keys win, the others' stay; before or after the subcommand.
TEST(CliContractTest, RepeatedConfigFilesMergeInOrder) {
  const std::string dir = TempDir("merge_config");
  uwbsar::testing::WriteTextFile(dir + "/robot.yaml",
                                 "slam:\n  occupied_fraction: 0.5\n  occupancy_resolution_m: 0.1\n"
                                 "backend:\n  calibration_scale_mean: 0.01\n");
  uwbsar::testing::WriteTextFile(dir + "/calibration.yaml",
                                 "# uwbsar calibrate\nbackend:\n  calibration_scale_mean: 0.02\n");
  for (const std::string& args :
       {"--config " + dir + "/robot.yaml --config " + dir + "/calibration.yaml config",
        "--config " + dir + "/robot.yaml config --config " + dir + "/calibration.yaml"}) {
    const CliRun r = Uwbsar(args);
    ASSERT_EQ(r.exit_code, 0) << args << ": " << r.output;
    EXPECT_TRUE(Has(r.output, "occupied_fraction: 0.5\n")) << r.output;
    EXPECT_TRUE(Has(r.output, "occupancy_resolution_m: 0.1\n")) << r.output;
    EXPECT_TRUE(Has(r.output, "calibration_scale_mean: 0.02\n")) << r.output;
  }
  // Each file is still checked: an unknown key names its file and line.
  uwbsar::testing::WriteTextFile(dir + "/bad.yaml", "slam:\n  occupied_fractoin: 0.5\n");
  const CliRun r = Uwbsar("--config " + dir + "/robot.yaml --config " + dir + "/bad.yaml config");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r.output, "bad.yaml:2")) << r.output;
}

// `config` printed 0.59999999999999998; now the shortest form that reads back the same, and
// its output read back as a configuration prints the same text.
TEST(CliContractTest, ConfigPrintsShortestRoundTripNumbers) {
  const std::string dir = TempDir("shortest");
  const CliRun r = Uwbsar("config");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Has(r.output, "occupied_fraction: 0.6\n")) << r.output;
  EXPECT_TRUE(Has(r.output, "occupancy_resolution_m: 0.05\n")) << r.output;
  EXPECT_FALSE(Has(r.output, "9999999")) << r.output;
  EXPECT_FALSE(Has(r.output, "0000001")) << r.output;
  uwbsar::testing::WriteTextFile(dir + "/all.yaml", r.output);
  const CliRun again = Uwbsar("--config " + dir + "/all.yaml config");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(again.output, r.output);
}

// `loops --out`, `match --out` and `optimize` did not say what they wrote.
TEST(CliContractTest, EveryCommandListsWhatItWrote) {
  const std::string dir = TempDir("listing");
  uwbsar::testing::WriteTextFile(
      dir + "/graph.g2o",
      "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n");
  CliRun r = Uwbsar("optimize " + dir + "/graph.g2o --out " + dir + "/out.g2o --tum " + dir +
                    "/out.tum --png " + dir + "/out.png");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"/out.g2o\n", "/out.tum\n", "/out.png\n"}) {
    EXPECT_TRUE(Has(r.output, "wrote " + dir + f)) << f << " in " << r.output;
  }
  // --json: stdout is the document alone, the list goes to stderr.
  r = Uwbsar("optimize " + dir + "/graph.g2o --json --out " + dir + "/j.g2o", false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(Has(r.output, "wrote ")) << r.output;
  EXPECT_TRUE(Has(Uwbsar("optimize " + dir + "/graph.g2o --json --out " + dir + "/j.g2o").output,
                  "wrote " + dir + "/j.g2o"));
  r = Uwbsar("optimize -q " + dir + "/graph.g2o --out " + dir + "/q.g2o");
  EXPECT_EQ(r.output, "");

  UWBSAR_NEED_SHARED_DATA("real/seed_corridor/regions/D1.png");
  fs::create_directories(dir + "/regions");
  for (const char* name : {"D1.png", "R1.png"}) {
    fs::copy_file(
        uwbsar::testing::SharedDataPath(std::string("real/seed_corridor/regions/") + name),
        dir + "/regions/" + name);
  }
  r = Uwbsar("match " + dir + "/regions/D1.png " + dir + "/regions/R1.png --out " + dir + "/m");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Has(r.output, "wrote " + dir + "/m/match.png\n")) << r.output;
  EXPECT_TRUE(Has(r.output, "wrote " + dir + "/m/match.json\n")) << r.output;
  r = Uwbsar("loops --images " + dir + "/regions --out " + dir + "/l");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"pairs.csv", "pairs.md", "loops.json", "matrix.png"}) {
    EXPECT_TRUE(Has(r.output, "wrote " + dir + "/l/" + f + "\n")) << f << " in " << r.output;
  }
}

}  // namespace
