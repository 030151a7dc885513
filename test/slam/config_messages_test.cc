// What a refused --config file says (issue 49 item 5): an invalid value names the file and line
// that set it and its key, a radar by its name; an unknown key suggests the closest known one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "slam/app_config_io.h"
#include "test/slam/config_refusal.h"

namespace uwbsar {
namespace {

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("uwbsar_config_messages_" + std::to_string(::getpid()) + "_" + name))
                               .string();
  std::ofstream(path) << text;
  return path;
}

std::string RefusalOfFiles(const std::vector<std::string>& paths) {
  try {
    LoadConfigs(paths);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ConfigMessagesTest, AnInvalidValueNamesTheFileAndLineThatSetItAndItsKey) {
  EXPECT_EQ(RefusalOf("imaging:\n  mode: paper\nslam:\n  map_resolution_m: 0\n", "bad.yaml"),
            "bad.yaml:4: 'slam.map_resolution_m' must be in (0, 10]");
  // A radar by its name, at the line of the file that set the key.
  EXPECT_EQ(RefusalOf("radars:\n  - name: right\n    min_range_m: -1\n"),
            "x.yaml:3: 'radars[right].min_range_m' must be >= 0");
  // Of two files, the one that set the key last.
  const std::string robot = WriteTemp("robot.yaml", "slam:\n  keyframe_queue_size: 0\n");
  const std::string calib =
      WriteTemp("calib.yaml", "imaging:\n  mode: paper\nslam:\n  keyframe_queue_size: 0\n");
  EXPECT_EQ(RefusalOfFiles({robot, calib}), calib + ":4: 'slam.keyframe_queue_size' must be >= 1");
  EXPECT_EQ(RefusalOfFiles({calib, WriteTemp("other.yaml", "imaging:\n  mode: paper\n")}),
            calib + ":4: 'slam.keyframe_queue_size' must be >= 1");
  // A key no file set (a rule across keys) keeps naming the files.
  EXPECT_EQ(RefusalOf("slam:\n  map_resolution_m: 2\n"),
            "x.yaml: 'slam.occupancy_resolution_m' must be in [slam.map_resolution_m, 10]");
}

TEST(ConfigMessagesTest, AnUnknownKeySuggestsTheClosestKnownOne) {
  EXPECT_EQ(RefusalOf("imaging:\n  pixle_size_m: 0.01\n"),
            "x.yaml:2: unknown key 'imaging.pixle_size_m' (did you mean 'imaging.pixel_size_m'?)");
  EXPECT_EQ(RefusalOf("slma:\n  map_resolution_m: 0.01\n"),
            "x.yaml:1: unknown key 'slma' (did you mean 'slam'?)");
  // Nothing close: no suggestion.
  EXPECT_EQ(RefusalOf("imaging:\n  colour: red\n"), "x.yaml:2: unknown key 'imaging.colour'");
}

}  // namespace
}  // namespace uwbsar
