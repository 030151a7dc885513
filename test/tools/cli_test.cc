// The `uwbsar` executable as a user meets it: exit codes, one-line errors, outputs.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "test/cli_runner.h"

namespace {

using uwbsar::testing::CliRun;
using uwbsar::testing::Uwbsar;

std::string TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("uwbsar_cli_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

void WriteFile(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(CliTest, HelpDocumentsExitCodes) {
  const CliRun r = Uwbsar("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("Exit codes"), std::string::npos);
  EXPECT_NE(r.output.find("image"), std::string::npos);
}

TEST(CliTest, UnknownFlagIsUsageError) { EXPECT_EQ(Uwbsar("image --no-such-flag").exit_code, 2); }

TEST(CliTest, ConfigWithUnknownKeyIsBadInputNamingKeyAndFile) {
  const std::string dir = TempDir("config");
  WriteFile(dir + "/bad.yaml", "imaging:\n  pixle_size_m: 0.01\n");
  const CliRun r = Uwbsar("--config " + dir + "/bad.yaml config");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.output.find("bad.yaml:2"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("imaging.pixle_size_m"), std::string::npos) << r.output;
}

// Issue 49 item 5: a mistyped option is named (not the required option it left out), with the
// closest known one; a mistyped subcommand likewise.
TEST(CliTest, AnUnknownOptionOrSubcommandIsNamedWithTheClosestKnownOne) {
  const std::string dir = TempDir("unknown_option");
  WriteFile(dir + "/x.bag", "");
  CliRun r = Uwbsar("map " + dir + "/x.bag --outt " + dir + "/out");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("uwbsar: error: unknown option '--outt' (did you mean '--out'?)"),
            std::string::npos)
      << r.output;
  r = Uwbsar("mpa x.bag");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("unknown subcommand 'mpa' (did you mean 'map'?)"), std::string::npos)
      << r.output;
  r = Uwbsar("map " + dir + "/x.bag --out " + dir + "/out --colour red");
  EXPECT_NE(r.output.find("unknown option '--colour' (see"), std::string::npos) << r.output;
}

TEST(CliTest, ACommandLineErrorPointsToTheCommandsOwnHelp) {
  CliRun r = Uwbsar("map");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("(see uwbsar map --help)"), std::string::npos) << r.output;
  r = Uwbsar("nosuchcommand");
  EXPECT_NE(r.output.find("(see uwbsar --help)"), std::string::npos) << r.output;
}

// The main job first, then the tools around a map, then the developers' tools.
TEST(CliTest, HelpListsTheCommandsInTheOrderAUserNeedsThem) {
  const CliRun r = Uwbsar("--help");
  ASSERT_EQ(r.exit_code, 0);
  std::size_t last = 0;
  std::string previous = "(start)";
  for (const char* name :
       {"demo", "map", "localize", "run", "merge", "calibrate", "check", "compare", "info",
        "simulate", "export-pcd", "config", "Developer tools:", "image", "match", "loops",
        "detectors", "optimize"}) {
    const std::string line = name[0] == 'D' ? "\n" + std::string(name) + "\n"  // the heading
                                            : "\n  " + std::string(name) + " ";
    const std::size_t at = r.output.find(line);
    ASSERT_NE(at, std::string::npos) << name << " missing:\n" << r.output;
    EXPECT_GT(at, last) << name << " listed before " << previous << ":\n" << r.output;
    last = at;
    previous = name;
  }
}

TEST(CliTest, MalformedTextLogNamesFileAndLine) {
  const std::string dir = TempDir("log");
  WriteFile(dir + "/run.log", "odom 100 0 0 0\nscan 200 0 3 1.0 2.0\n");
  const CliRun r = Uwbsar("image --log " + dir + "/run.log --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.output.find("run.log:2"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out/strip_float.tif"));
}

TEST(CliTest, ImageFromTextLogWritesEveryOutput) {
  const std::string dir = TempDir("image");
  WriteFile(dir + "/run.log", uwbsar::testing::TinyTextLog(1000));
  const CliRun r = Uwbsar("image --log " + dir + "/run.log --out " + dir + "/out --mode coherent");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"strip_raw.png", "strip_positive.png", "strip_enhanced.png",
                        "strip_logmag.png", "strip_float.tif", "strip_grid.yaml"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/out/" + f)) << f;
  }
  EXPECT_NE(r.output.find("25 imaged"), std::string::npos) << r.output;
}

}  // namespace
