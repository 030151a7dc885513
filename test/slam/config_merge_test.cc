// Repeated --config files merged in order, numbers written shortest, and sessions saved with
// the older long numbers still compatible (issue 29).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/app_config_io.h"
#include "core/shortest_number.h"
#include "slam/config/config_fingerprint.h"

namespace uwbsar {
namespace {

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("uwbsar_config_merge_" + std::to_string(::getpid()) + "_" + name))
                               .string();
  std::ofstream(path) << text;
  return path;
}

// Radars merge by name rather than as a whole list since issue 49 (radar_list_merge_test.cc).
TEST(ConfigMergeTest, LaterFilesWinKeyByKeyAndRadarsByName) {
  const std::string robot = WriteTemp("robot.yaml",
                                      "slam:\n  occupied_fraction: 0.5\n"
                                      "radars:\n  - name: left\n    topic: /a\n"
                                      "  - name: right\n    topic: /b\n");
  const std::string calib =
      WriteTemp("calib.yaml",
                "slam:\n  occupancy_resolution_m: 0.1\nradars:\n  - name: right\n"
                "    max_range_m: 2.5\n  - name: only\n    topic: /c\n  - name: left\n");
  const Config c = LoadConfigs({robot, calib});
  EXPECT_DOUBLE_EQ(c.slam.occupied_fraction, 0.5);       // kept from the first
  EXPECT_DOUBLE_EQ(c.slam.occupancy_resolution_m, 0.1);  // from the second
  ASSERT_EQ(c.radars.size(), 3u);                        // merged by name, one added
  EXPECT_EQ(c.radars[0].topic, "/a");
  EXPECT_EQ(c.radars[1].topic, "/b");              // kept from the first ...
  EXPECT_DOUBLE_EQ(c.radars[1].max_range_m, 2.5);  // ... with the second's key
  EXPECT_EQ(c.radars[2].name, "only");
  EXPECT_EQ(ConfigToYaml(LoadConfigs({})), ConfigToYaml(AppConfig{}));
  EXPECT_EQ(ConfigToYaml(LoadConfigs({robot})), ConfigToYaml(LoadConfig(robot)));
  // The merged result is validated, naming the file and line that set the refused value.
  const std::string bad = WriteTemp("bad.yaml", "slam:\n  occupied_fraction: 7\n");
  try {
    LoadConfigs({robot, bad});
    FAIL() << "an invalid merged configuration was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).find(bad + ":2: 'slam.occupied_fraction'"), 0u) << e.what();
  }
}

TEST(ConfigMergeTest, NumbersAreWrittenShortest) {
  EXPECT_EQ(ShortestNumber(0.6), "0.6");
  EXPECT_EQ(ShortestNumber(0.05), "0.05");
  EXPECT_EQ(ShortestNumber(7.29e9), "7290000000");
  EXPECT_EQ(ShortestNumber(1e-10), "1.0e-10");  // a number to YAML 1.1 readers too
  EXPECT_EQ(ShortestNumber(-2.5), "-2.5");
  EXPECT_EQ(ShortestNumber(3.0), "3");
  EXPECT_EQ(std::stod(ShortestNumber(0.1 + 0.2)), 0.1 + 0.2);
  EXPECT_DOUBLE_EQ(RoundToDigits(1.23456789, 6), 1.23457);
}

TEST(ConfigMergeTest, SessionsWithLongNumbersStayCompatible) {
  const Config config;
  std::string old = ConfigFingerprint(config);
  const std::string key = "imaging.pixel_size_m: ";
  const std::size_t at = old.find(key);
  ASSERT_NE(at, std::string::npos) << old;
  const std::size_t end = old.find('\n', at);
  old.replace(at, end - at, key + "0.0050000000000000001");  // as sessions wrote it before
  EXPECT_EQ(FingerprintDifference(old, config), "");
  old.replace(at, old.find('\n', at) - at, key + "0.01");
  EXPECT_NE(FingerprintDifference(old, config), "");
}

}  // namespace
}  // namespace uwbsar
