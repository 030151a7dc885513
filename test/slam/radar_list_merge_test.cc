// A --config file's `radars:` list merges into the one in effect by name (issue 49): a robot
// file that changes one key of one radar keeps the other radar; a new name adds a radar, and
// `remove: true` removes one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/app_config_io.h"
#include "test/slam/config_refusal.h"

namespace uwbsar {
namespace {

std::string Yaml(const RadarConfig& radar) { return ConfigToYaml(radar); }

TEST(RadarListMergeTest, ChangingOneKeyOfOneRadarKeepsTheOtherRadarExactly) {
  const AppConfig c =
      LoadConfigFromString("radars:\n  - name: left\n    max_range_m: 2.5\n", "r.yaml");
  const std::vector<RadarConfig> defaults = DefaultRadars();
  ASSERT_EQ(c.radars.size(), 2u);
  RadarConfig left = defaults[0];
  left.max_range_m = 2.5;
  EXPECT_EQ(Yaml(c.radars[0]), Yaml(left));
  EXPECT_EQ(Yaml(c.radars[1]), Yaml(defaults[1]));  // every field of the right one
  // The same over an earlier file, the right radar's key from a later one.
  const std::string robot = (std::filesystem::temp_directory_path() /
                             ("uwbsar_radar_merge_" + std::to_string(::getpid()) + ".yaml"))
                                .string();
  std::ofstream(robot) << "radars:\n  - name: left\n    max_range_m: 2.5\n";
  const std::string right =
      (std::filesystem::path(robot).parent_path() / ("r" + std::to_string(::getpid()) + ".yaml"))
          .string();
  std::ofstream(right) << "radars:\n  - name: right\n    range_offset_m: 0.05\n";
  const Config merged = LoadConfigs({robot, right});
  RadarConfig right_radar = defaults[1];
  right_radar.range_offset_m = 0.05;
  ASSERT_EQ(merged.radars.size(), 2u);
  EXPECT_EQ(Yaml(merged.radars[0]), Yaml(left));
  EXPECT_EQ(Yaml(merged.radars[1]), Yaml(right_radar));
  std::filesystem::remove(robot);
  std::filesystem::remove(right);
}

TEST(RadarListMergeTest, ANewNameAddsARadarFromTheDefaultsAndMustGiveItsTopic) {
  const AppConfig c = LoadConfigFromString(
      "radars:\n  - name: left\n  - name: right\n  - name: front\n    topic: /front/readings\n"
      "    boresight_yaw_deg: 0\n",
      "r.yaml");
  ASSERT_EQ(c.radars.size(), 3u);
  RadarConfig front;  // the documented per-radar defaults
  front.name = "front";
  front.topic = "/front/readings";
  front.boresight_yaw_deg = 0;
  EXPECT_EQ(Yaml(c.radars[2]), Yaml(front));
  EXPECT_EQ(Yaml(c.radars[0]), Yaml(DefaultRadars()[0]));
  EXPECT_EQ(RefusalOf("radars:\n  - name: left\n    mount_x_m: 0.1\n  - name: front\n"),
            "x.yaml:4: 'radars[1]' adds 'front' (no item of that name) and must give 'topic'");
  // A file written as the whole list (one radar of another name) is refused, not run with the
  // default radars beside it; removing them first gives the one radar.
  const std::string one_radar = "  - name: p440\n    topic: /p440/readings\n";
  EXPECT_EQ(RefusalOf("radars:\n" + one_radar),
            "x.yaml:2: 'radars[0]' adds 'p440' beside 'left', 'right', which this list does not "
            "name: keep each with '- name: NAME' or remove it with '- {name: NAME, remove: true}'");
  const Config one = LoadConfigFromString(
      "radars:\n  - {name: left, remove: true}\n  - {name: right, remove: true}\n" + one_radar,
      "r.yaml");
  ASSERT_EQ(one.radars.size(), 1u);
  EXPECT_EQ(one.radars[0].name, "p440");
}

TEST(RadarListMergeTest, ARadarIsRemovedByName) {
  const AppConfig c = LoadConfigFromString("radars:\n  - {name: right, remove: true}\n", "r.yaml");
  ASSERT_EQ(c.radars.size(), 1u);
  EXPECT_EQ(Yaml(c.radars[0]), Yaml(DefaultRadars()[0]));
  EXPECT_EQ(RefusalOf("radars:\n  - {name: back, remove: true}\n"),
            "x.yaml:2: 'radars[0]' removes 'back', which is not listed");
  EXPECT_EQ(RefusalOf("radars:\n  - {name: right, remove: true, max_range_m: 2}\n"),
            "x.yaml:2: 'radars[0]' removes 'right' and gives only name and remove");
  EXPECT_EQ(RefusalOf("radars:\n  - {name: right, remove: false}\n"),
            "x.yaml:2: 'radars[0].remove' must be true (leave it out to change 'right')");
  EXPECT_EQ(RefusalOf("radars:\n  - {name: left, remove: true}\n  - {name: right, remove: true}\n"),
            "x.yaml:2: 'radars' must list at least one radar");
  // `uwbsar config` prints a file that loads back to the same radars.
  EXPECT_EQ(ConfigToYaml(LoadConfigFromString(ConfigFileYaml(c), "printed.yaml")), ConfigToYaml(c));
  EXPECT_EQ(ConfigFileYaml(AppConfig{}), ConfigToYaml(AppConfig{}));
}

TEST(RadarListMergeTest, AnEntryWithoutANameIsRefusedNamingFileLineAndKey) {
  EXPECT_EQ(RefusalOf("radars:\n  - name: left\n    max_range_m: 2.5\n  - max_range_m: 2.5\n"),
            "x.yaml:4: 'radars[1]' has no 'name': entries of 'radars' change, add or remove the "
            "item of that name");
  EXPECT_EQ(RefusalOf("radars:\n  - name: left\n  - name: left\n    max_range_m: 2\n"),
            "x.yaml:3: 'radars[1]' names 'left' a second time");
  EXPECT_EQ(RefusalOf("radars: []\n"),
            "x.yaml:1: 'radars' is empty; its entries change, add or remove items by name "
            "(remove one with {name: NAME, remove: true})");
}

TEST(RadarListMergeTest, TheRobotTemplateLoadsAndStatesTheDefaults) {
  const std::string path = std::string(UWBSAR_SOURCE_DIR) + "/config/my_robot.yaml";
  EXPECT_EQ(ConfigToYaml(LoadConfig(path)), ConfigToYaml(AppConfig{}));
  EXPECT_EQ(
      ConfigToYaml(LoadConfigs({std::string(UWBSAR_SOURCE_DIR) + "/config/robot.yaml", path})),
      ConfigToYaml(LoadConfig(std::string(UWBSAR_SOURCE_DIR) + "/config/robot.yaml")));
}

}  // namespace
}  // namespace uwbsar
