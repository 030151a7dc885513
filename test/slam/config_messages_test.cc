// What a refused --config file says (issue 49 item 5): an invalid value names the file and line
// that set it and its key, a radar by its name; an unknown key suggests the closest known one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/app_config_io.h"
#include "backend/navigation_grid_config.h"
#include "core/config_require.h"
#include "frontend/wall_profile_config.h"
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

/// "'<key>' <rule>" of the refusal `validate` throws, as a section's own validator words it.
template <class F>
std::string OwnRefusalOf(F validate) {
  try {
    validate();
  } catch (const ConfigValueError& e) {
    return "'" + e.key() + "' " + e.rule();
  }
  return "";
}

// Issue 46 item 4: slam.navigation.* is validated beside its struct in backend/, the wall
// settings beside theirs in frontend/; the whole file refuses them with the same words.
TEST(ConfigMessagesTest, NavigationAndWallSettingsAreRefusedBesideTheirDeclaration) {
  NavigationGridConfig navigation;
  navigation.ray_width_m = 2;
  EXPECT_EQ(OwnRefusalOf([&] { Validate(navigation, "x.yaml"); }),
            "'slam.navigation.ray_width_m' must be in [0, 1]");
  EXPECT_EQ(RefusalOf("slam:\n  navigation:\n    ray_width_m: 2\n"),
            "x.yaml:3: " + OwnRefusalOf([&] { Validate(navigation, "x.yaml"); }));

  WallProfileConfig walls;
  walls.landmarks.min_strips = 9;
  EXPECT_EQ(OwnRefusalOf([&] { Validate(walls, "x.yaml"); }),
            "'place_recognition.wall_profiles.landmarks.min_strips' must be in [3, strips]");
  EXPECT_EQ(OwnRefusalOf([&] { Validate(walls.landmarks, "x.yaml"); }),
            OwnRefusalOf([&] { Validate(walls, "x.yaml"); }));
  EXPECT_EQ(
      RefusalOf("place_recognition:\n  wall_profiles:\n    landmarks:\n      min_strips: 9\n"),
      "x.yaml:4: " + OwnRefusalOf([&] { Validate(walls, "x.yaml"); }));
  walls = WallProfileConfig();
  walls.max_gap = 1;
  EXPECT_EQ(OwnRefusalOf([&] { Validate(walls, "x.yaml"); }),
            "'place_recognition.wall_profiles.max_gap' must be in [wall_profiles.min_gap, 100]");
  EXPECT_EQ(RefusalOf("place_recognition:\n  wall_profiles:\n    max_gap: 1\n"),
            "x.yaml:3: " + OwnRefusalOf([&] { Validate(walls, "x.yaml"); }));
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
