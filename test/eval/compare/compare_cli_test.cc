// `uwbsar compare` and `uwbsar export-pcd` as a user meets them: exit codes, one-line
// errors naming the file, outputs only on success.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "eval/compare/pcd_export.h"
#include "test/cli_runner.h"
#include "test/shared_data.h"
#include "test_maps.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;

using testing::CliRun;
using testing::Uwbsar;

TEST(CompareCliTest, GridAgainstItselfPrintsPerfectScoresAndWritesOutputs) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const std::string dir = testing::FreshDir("cli_self");
  const std::string map = testing::SeedLabYaml();
  const CliRun r = Uwbsar("compare " + map + " " + map + " --out " + dir + "/out");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("= 0.0 %"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("F1 1.000"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("SAR->LiDAR: mean 0.000 m, p95 0.000 m"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_regular_file(dir + "/out/overlay.png"));
  EXPECT_TRUE(fs::is_regular_file(dir + "/out/metrics.json"));
}

TEST(CompareCliTest, JsonFlagPrintsTheMetricsDocument) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const std::string dir = testing::FreshDir("cli_json");
  const std::string map = testing::SeedLabYaml();
  const CliRun r =
      Uwbsar("compare " + map + " " + map + " --align origin --json --out " + dir, false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["metrics"]["f1"].get<double>(), 1.0);
  EXPECT_EQ(j["alignment"]["mode"], "origin");
}

TEST(CompareCliTest, FixedAlignmentAndInitAreParsedInMetresAndDegrees) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const std::string dir = testing::FreshDir("cli_fixed");
  const std::string map = testing::SeedLabYaml();
  CliRun r = Uwbsar("compare " + map + " " + map + " --align 0.05,0,0 --json --out " + dir, false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  nlohmann::json j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["alignment"]["mode"], "fixed");
  EXPECT_DOUBLE_EQ(j["alignment"]["T_lidar_sar"]["x_m"].get<double>(), 0.05);
  EXPECT_GT(j["metrics"]["difference_ratio"].get<double>(), 0.0);
  r = Uwbsar("compare " + map + " " + map + " --init 0.1,-0.1,2 --json --out " + dir, false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  j = nlohmann::json::parse(r.output);
  EXPECT_NEAR(j["alignment"]["T_initial"]["yaw_deg"].get<double>(), 2.0, 1e-9);
  EXPECT_NEAR(j["alignment"]["T_lidar_sar"]["x_m"].get<double>(), 0.0, 1e-3);  // ICP undid it
}

TEST(CompareCliTest, MalformedTransformIsUsageError) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const std::string map = testing::SeedLabYaml();
  EXPECT_EQ(Uwbsar("compare " + map + " " + map + " --out /tmp/x --align 1,2").exit_code, 2);
  EXPECT_EQ(Uwbsar("compare " + map + " " + map + " --out /tmp/x --align icp,1,2").exit_code, 2);
  EXPECT_EQ(
      Uwbsar("compare " + map + " " + map + " --out /tmp/x --align origin --init 0,0,0").exit_code,
      2);
}

TEST(CompareCliTest, BadInputIsExitCode3NamingTheFileAndWritesNothing) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const std::string dir = testing::FreshDir("cli_bad");
  std::ofstream(dir + "/missing.yaml") << "image: gone.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  std::ofstream(dir + "/zero.yaml") << "image: gone.pgm\nresolution: 0\norigin: [0, 0, 0]\n";
  std::ofstream(dir + "/hdr.pgm", std::ios::binary) << "P7\n2 2\n255\nabcd";
  std::ofstream(dir + "/hdr.yaml") << "image: hdr.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  OccupancyGrid far = testing::SeedLabGrid();
  far.origin.y_m += 50.0;
  testing::WriteMapServer(far, dir, "far");
  const std::string map = testing::SeedLabYaml();
  for (const std::string name : {"missing", "zero", "hdr", "far"}) {
    const std::string out = dir + "/out_" + name;
    const CliRun r = Uwbsar("compare " + dir + "/" + name + ".yaml " + map + " --out " + out);
    EXPECT_EQ(r.exit_code, 3) << name << ": " << r.output;
    EXPECT_NE(r.output.find(name + "."), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "one line: " << r.output;
    EXPECT_FALSE(fs::exists(out)) << name;
  }
}

// Issue 45 item 14: an origin of 1e300 m reached PCL, which printed a line of its own before
// uwbsar's error. A map's origin lies within 1000 km, like a session's coordinates.
TEST(CompareCliTest, AFarOriginIsRefusedNamingFileAndKeyBeforePclSeesIt) {
  const std::string dir = testing::FreshDir("cli_far_origin");
  const std::string hall = std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall";
  std::ofstream(dir + "/far.yaml")
      << "image: " << hall << ".pgm\nresolution: 0.05\norigin: [1e300, 0, 0]\n";
  const CliRun r = Uwbsar("compare " + dir + "/far.yaml " + hall + ".yaml --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("far.yaml:3: map key 'origin' x is 1e+300 m, beyond 1e+06 m"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "one line: " << r.output;
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

TEST(ExportPcdCliTest, WritesOccupiedCellsThatPclReadsBack) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const std::string dir = testing::FreshDir("cli_pcd");
  const CliRun r = Uwbsar("export-pcd " + testing::SeedLabYaml() + " --out " + dir + "/lab.pcd");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::size_t expected = OccupiedCellPoints(testing::SeedLabGrid()).size();
  EXPECT_NE(r.output.find(std::to_string(expected) + " occupied cells"), std::string::npos)
      << r.output;
  EXPECT_EQ(ReadPcd(dir + "/lab.pcd").size(), expected);
  const CliRun bad = Uwbsar("export-pcd " + dir + "/none.yaml --out " + dir + "/x.pcd");
  EXPECT_EQ(bad.exit_code, 3) << bad.output;
  EXPECT_FALSE(fs::exists(dir + "/x.pcd"));
}

}  // namespace
}  // namespace uwbsar
