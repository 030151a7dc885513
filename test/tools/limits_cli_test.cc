// The limits as a user meets them: hostile sizes are refused with exit 3
// and one line naming the key or file, before any work; one odometry outlier does not
// break a run. Each command runs under a 3 GB address-space cap, so a regression fails
// the test instead of exhausting the machine.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "test/cli_runner.h"

namespace {

using uwbsar::testing::CliRun;
using uwbsar::testing::RunCommand;

std::string TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("uwbsar_limits_cli_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

void WriteFile(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

CliRun Capped(const std::string& args) {
  return RunCommand("ulimit -v 3000000; " + std::string(UWBSAR_BIN) + " " + args);
}

/// The bundled room (our own map), as the map every comparison needs.
std::string SeedHall() {
  return std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml";
}

TEST(LimitsCliTest, ConfigFromADeviceIsRefused) {
  const CliRun r = Capped("--config /dev/zero config");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("/dev/zero: configuration file is not a regular file"), std::string::npos)
      << r.output;
}

TEST(LimitsCliTest, SizeExplodingConfigValuesAreRefusedNamingTheKey) {
  const std::string dir = TempDir("config");
  WriteFile(dir + "/fine.yaml", "slam:\n  map_resolution_m: 1.0e-9\n");
  CliRun r = Capped("--config " + dir + "/fine.yaml config");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("'slam.map_resolution_m'"), std::string::npos) << r.output;
  // A command-line pixel size is checked the same way, before any imaging.
  r = Capped("image --synthetic straight --resolution 1e-9 --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("--resolution: 'imaging.pixel_size_m'"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("failed to allocate"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out/strip_float.tif"));
}

TEST(LimitsCliTest, MapImageDeclaringHugeSizeIsRefusedBeforeDecoding) {
  // A 20000 x 20000 PNG declared by a small file (the IHDR of an 8 x 8 image patched).
  const std::string dir = TempDir("bomb");
  ASSERT_TRUE(cv::imwrite(dir + "/small.png", cv::Mat(8, 8, CV_8UC1, cv::Scalar(254))));
  std::ifstream in(dir + "/small.png", std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  std::string png = bytes.str();
  const char size[8] = {0, 0, 0x4e, 0x20, 0, 0, 0x4e, 0x20};
  png.replace(16, 8, size, 8);
  WriteFile(dir + "/bomb.png", png);
  const std::string yaml = dir + "/bomb.yaml";
  WriteFile(yaml, "image: bomb.png\nresolution: 0.05\norigin: [0, 0, 0]\n");
  for (const std::string& args :
       {"export-pcd " + yaml + " --out " + dir + "/m.pcd",
        "compare " + yaml + " " + SeedHall() + " --out " + dir + "/cmp",
        "simulate --map " + yaml + " --route depart-return --out " + dir + "/bag"}) {
    const CliRun r = Capped(args);
    EXPECT_EQ(r.exit_code, 3) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("bomb.png: map image PNG declares 20000 x 20000 pixels"),
              std::string::npos)
        << args << "\n"
        << r.output;
  }
}

TEST(LimitsCliTest, OneOdometryOutlierDoesNotBreakImage) {
  // The tiny log of CliTest.ImageFromTextLogWritesEveryOutput with one sample at x = 1e20
  // (it used to abort inside OpenCV, allocating 9 TB) and one 100 km away.
  const std::string dir = TempDir("outlier");
  std::string log;
  for (int i = 0; i <= 30; ++i) {
    const char* x = i == 10 ? "1e20" : (i == 20 ? "100000" : nullptr);
    log += "odom " + std::to_string(1000000000LL + i * 20000000LL) + " " +
           (x ? std::string(x) : std::to_string(i * 0.01)) + " 0 0\n";
  }
  for (int i = 0; i < 25; ++i) {
    log += "scan " + std::to_string(1010000000LL + i * 20000000LL) + " 0 1000";
    for (int k = 0; k < 1000; ++k) log += (k == 200 ? " 1.0" : " 0");
    log += "\n";
  }
  WriteFile(dir + "/run.log", log);
  const CliRun r = Capped("image --log " + dir + "/run.log --out " + dir + "/out");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("25 imaged"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("dropped as an outlier"), std::string::npos) << r.output;
}

}  // namespace
