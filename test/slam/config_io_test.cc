#include <gtest/gtest.h>

#include <array>
#include <string>

#include "app/app_config_io.h"
#include "test/slam/config_refusal.h"

namespace uwbsar {
namespace {

TEST(ConfigIoTest, DefaultYamlEqualsInClassDefaults) {
  // config/default.yaml documents every field; it must not drift from the structs.
  const AppConfig from_file = LoadConfig(std::string(UWBSAR_SOURCE_DIR) + "/config/default.yaml");
  EXPECT_EQ(ConfigToYaml(from_file), ConfigToYaml(AppConfig{}));
}

TEST(ConfigIoTest, DefaultsMatchThePaper) {
  const Config c;
  EXPECT_DOUBLE_EQ(c.pulse.sampling_frequency_hz, 23.328e9);
  EXPECT_DOUBLE_EQ(c.pulse.center_frequency_hz, 7.29e9);
  EXPECT_DOUBLE_EQ(c.imaging.pixel_size_m, 0.005);
  EXPECT_DOUBLE_EQ(c.gating.min_travel_m, 0.003);
  ASSERT_EQ(c.radars.size(), 2u);
  EXPECT_DOUBLE_EQ(c.radars[0].boresight_yaw_deg, 90.0);
  EXPECT_DOUBLE_EQ(c.radars[1].boresight_yaw_deg, -90.0);
  EXPECT_DOUBLE_EQ(c.radars[0].min_range_m, 0.4);
  EXPECT_DOUBLE_EQ(c.radars[0].max_range_m, 3.0);
}

TEST(ConfigIoTest, PartialFileKeepsOtherDefaults) {
  const Config c = LoadConfigFromString("imaging:\n  mode: coherent\n", "t.yaml");
  EXPECT_EQ(c.imaging.mode, ImagingMode::kCoherent);
  EXPECT_DOUBLE_EQ(c.imaging.pixel_size_m, 0.005);
  EXPECT_EQ(c.radars.size(), 2u);
}

TEST(ConfigIoTest, UnknownKeyNamesKeyFileAndLine) {
  try {
    LoadConfigFromString("imaging:\n  mode: paper\n  pixel_sise_m: 0.01\n", "robot.yaml");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("robot.yaml:3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("imaging.pixel_sise_m"), std::string::npos) << msg;
  }
}

TEST(ConfigIoTest, UnknownKeyInsideListEntryIsAnError) {
  EXPECT_THROW(LoadConfigFromString("radars:\n  - name: a\n    fov_deg: 10\n", "r.yaml"),
               ConfigError);
}

TEST(ConfigIoTest, WrongTypeIsAnError) {
  try {
    LoadConfigFromString("imaging:\n  pixel_size_m: five\n", "x.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("imaging.pixel_size_m"), std::string::npos);
  }
  EXPECT_THROW(LoadConfigFromString("imaging: 3\n", "x.yaml"), ConfigError);
  EXPECT_THROW(LoadConfigFromString("radars: {a: 1}\n", "x.yaml"), ConfigError);
}

TEST(ConfigIoTest, InvalidValuesAreRejected) {
  EXPECT_THROW(LoadConfigFromString("imaging:\n  mode: fancy\n", "x.yaml"), ConfigError);
  EXPECT_THROW(LoadConfigFromString("imaging:\n  pixel_size_m: 0\n", "x.yaml"), ConfigError);
  EXPECT_THROW(LoadConfigFromString("imaging:\n  pixel_size_m: .nan\n", "x.yaml"), ConfigError);
  EXPECT_THROW(LoadConfigFromString("radars: []\n", "x.yaml"), ConfigError);
  EXPECT_THROW(LoadConfigFromString("keyframe:\n  tile_spacing_m: 3\n", "x.yaml"), ConfigError);
  // One topic per stream: a bag or DDS cannot carry two types on one name.
  EXPECT_THROW(LoadConfigFromString("slam:\n  odometry_topic: /UWBradar0/readings\n", "x.yaml"),
               ConfigError);
  EXPECT_THROW(LoadConfigFromString("dds:\n  reliability: sometimes\n", "x.yaml"), ConfigError);
  EXPECT_THROW(LoadConfigFromString("dds:\n  domain_id: 300\n", "x.yaml"), ConfigError);
  EXPECT_THROW(LoadConfigFromString("dds:\n  map_topic: uwbsar/map\n", "x.yaml"), ConfigError);
  EXPECT_THROW(LoadConfigFromString("slam:\n  keyframe_queue_size: 0\n", "x.yaml"), ConfigError);
}

TEST(ConfigIoTest, AnOdometryCalibrationIsAFractionAndNeedsTheCalibrationOn) {
  const Config c = LoadConfigFromString("backend:\n  calibration_scale_mean: -0.005\n", "x.yaml");
  EXPECT_EQ(c.backend.CalibrationMean(), (std::array<double, 3>{-0.005, 0.0, 0.0}));
  const auto rejected = [](const std::string& text, const std::string& key) {
    try {
      LoadConfigFromString(text, "robot.yaml");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  rejected("backend:\n  calibration_scale_mean: -0.5\n", "backend.calibration_scale_mean");
  rejected("backend:\n  calibration_scale_mean: .nan\n", "backend.calibration_scale_mean");
  rejected("backend:\n  calibration_heading_drift_mean_rad_per_m: 0.2\n",
           "backend.calibration_heading_drift_mean_rad_per_m");
  rejected("backend:\n  calibration_rotation_mean: 3\n", "backend.calibration_rotation_mean");
  rejected("backend:\n  odometry_calibration: false\n  calibration_rotation_mean: 0.01\n",
           "backend.odometry_calibration");
}

TEST(ConfigIoTest, SyntaxErrorAndMissingFileAreReported) {
  EXPECT_THROW(LoadConfigFromString("imaging: [\n", "x.yaml"), ConfigError);
  EXPECT_THROW(LoadConfig("/nonexistent/uwbsar.yaml"), ConfigError);
}

TEST(ConfigIoTest, EmptyFileMeansDefaults) {
  EXPECT_EQ(ConfigToYaml(LoadConfigFromString("", "e.yaml")), ConfigToYaml(AppConfig{}));
}

TEST(ConfigIoTest, WrongShapeIsBadInputNamingFileLineAndKey) {
  struct Case {
    const char* yaml;
    const char* expect;
  } cases[] = {
      {"imaging:\n  mode: paper\n? [a, b]\n: 1\n", "x.yaml:3: a key in 'the top level'"},
      {"imaging:\n  ? {a: 1}\n  : 2\n", "x.yaml:2: a key in 'imaging' is not a plain name"},
      {"slam: 5\n", "x.yaml:1: 'slam' must be a mapping"},
      {"radars:\n  - 7\n", "x.yaml:2: 'radars[0]' must be a mapping"},
      {"imaging:\n  pixel_size_m: [1, 2]\n", "x.yaml:2: 'imaging.pixel_size_m' must be a value"},
  };
  for (const Case& c : cases) {
    try {
      LoadConfigFromString(c.yaml, "x.yaml");
      ADD_FAILURE() << "no error for " << c.yaml;
    } catch (const ConfigError& e) {  // exit 3, never a raw yaml-cpp exception (exit 1)
      EXPECT_NE(std::string(e.what()).find(c.expect), std::string::npos) << e.what();
    }
  }
}

// The first of two equal keys used to win silently: a robot file overriding a key it already
// set (or a section pasted twice) ran with the value the user did not read last.
TEST(ConfigIoTest, ADuplicateKeyOrSectionIsRefusedNamingFileLineAndDottedKey) {
  EXPECT_EQ(RefusalOf("imaging:\n  pixel_size_m: 0.005\n  pixel_size_m: 0.01\n"),
            "x.yaml:3: duplicate key 'imaging.pixel_size_m' (first at line 2)");
  EXPECT_EQ(RefusalOf("imaging:\n  mode: paper\nslam: {}\nimaging:\n  mode: coherent\n"),
            "x.yaml:4: duplicate key 'imaging' (first at line 1)");
  EXPECT_EQ(RefusalOf("radars:\n  - name: a\n    name: b\n"),
            "x.yaml:3: duplicate key 'radars[0].name' (first at line 2)");
  // The same key in two sections, or in two list items, is no duplicate.
  EXPECT_EQ(RefusalOf("radars:\n  - name: left\n    topic: /a\n  - name: right\n    topic: /b\n"),
            "");
}

TEST(ConfigIoTest, ASecondDocumentIsRefusedNamingItsLine) {
  EXPECT_EQ(RefusalOf("imaging:\n  mode: paper\n---\nimaging:\n  mode: coherent\n"),
            "x.yaml:3: a second YAML document (after '---'); a file holds one document");
  // One document, with or without its markers, is fine.
  EXPECT_EQ(RefusalOf("---\nimaging:\n  mode: paper\n...\n"), "");
}

// live.radar_model picks the radars' driver from the registry: a model nobody registered is
// refused naming the key and the models there are.
TEST(ConfigIoTest, AnUnknownRadarModelIsRefusedNamingTheKnownModels) {
  EXPECT_EQ(RefusalOf("live:\n  radar_model: lt103\n"),
            "x.yaml:2: 'live.radar_model' is 'lt103', not a known radar model (lt102)");
  EXPECT_EQ(RefusalOf("live:\n  radar_model: lt102\n"), "");
}

// `010` is 8 in YAML 1.1 (yaml-cpp) and 10 in YAML 1.2: refused rather than guessed.
TEST(ConfigIoTest, ANumberWithALeadingZeroIsRefusedNamingTheKey) {
  const std::string msg = RefusalOf("imaging:\n  num_threads: 010\n");
  EXPECT_EQ(msg.rfind("x.yaml:2: 'imaging.num_threads' has value '010' with a leading zero", 0), 0u)
      << msg;
  EXPECT_NE(RefusalOf("imaging:\n  pixel_size_m: -00.5\n").find("leading zero"), std::string::npos);
  EXPECT_EQ(RefusalOf("imaging:\n  pixel_size_m: 0.005\n"), "");  // 0.x is no leading zero
}

// Issue 45 item 9: navigation thresholds beyond the clamp, which log-odds never pass, made a
// grid with no occupied cell (or none freed but the robot's disc), and a 1e9 m cell a 4 x 4 grid
// 2e9 m away, exit 0. Each is refused naming the keys it contradicts.
TEST(ConfigIoTest, NavigationSettingsThatCancelThemselvesAreRefusedNamingTheKeys) {
  const std::string nav = "slam:\n  navigation:\n";
  EXPECT_EQ(RefusalOf(nav + "    log_odds_clamp: 2.0\n    occupied_log_odds: 3.0\n"),
            "x.yaml:4: 'slam.navigation.occupied_log_odds' must be below "
            "slam.navigation.log_odds_clamp: log-odds never pass the clamp, so no cell would be "
            "occupied");
  EXPECT_NE(RefusalOf(nav + "    occupied_log_odds: 5.0\n").find("log_odds_clamp"),
            std::string::npos);  // equal to the default clamp
  EXPECT_EQ(RefusalOf(nav + "    free_log_odds: -6.0\n"),
            "x.yaml:3: 'slam.navigation.free_log_odds' must be above minus "
            "slam.navigation.log_odds_clamp: log-odds never pass the clamp, so only the robot's "
            "swept disc would be free");
  EXPECT_EQ(RefusalOf("slam:\n  occupancy_resolution_m: 1.0e9\n"),
            "x.yaml:2: 'slam.occupancy_resolution_m' must be in [slam.map_resolution_m, 10]");
  EXPECT_EQ(RefusalOf("slam:\n  map_resolution_m: 20\n  occupancy_resolution_m: 20\n"),
            "x.yaml:2: 'slam.map_resolution_m' must be in (0, 10]");
  // Within the clamp, and at 10 m cells, they stand.
  EXPECT_EQ(RefusalOf(nav + "    occupied_log_odds: 4.9\n    free_log_odds: -4.9\n"), "");
  EXPECT_EQ(RefusalOf("slam:\n  occupancy_resolution_m: 10\n"), "");
}

}  // namespace
}  // namespace uwbsar
