// Configuration values whose implied sizes exceed the budgets
// of `limits:` are refused before any work, naming the key; configuration and YAML files
// are read only when they are small regular files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/app_config_io.h"
#include "core/bounded_file.h"
#include "core/yaml_file.h"
#include "test/slam/config_refusal.h"

namespace uwbsar {
namespace {

std::string Refusal(const std::string& yaml) { return RefusalOf(yaml, "cfg.yaml"); }

TEST(ConfigLimitsTest, SizeExplodingValuesAreRefusedNamingTheKey) {
  struct Case {
    const char* yaml;
    const char* key;
  };
  const Case cases[] = {
      {"slam:\n  map_resolution_m: 1.0e-4\n", "'slam.map_resolution_m'"},
      {"slam:\n  map_resolution_m: 1.0e-9\n", "'slam.map_resolution_m'"},
      {"imaging:\n  pixel_size_m: 1.0e-9\n", "'imaging.pixel_size_m'"},
      {"keyframe:\n  tile_spacing_m: 0.001\n", "'keyframe.tile_spacing_m'"},
      {"keyframe:\n  tile_length_m: 0.001\n  tile_spacing_m: 0.001\n", "'keyframe.tile_spacing_m'"},
      {"keyframe:\n  tile_length_m: 1000\n", "'keyframe.tile_length_m'"},
      {"keyframe:\n  margin_m: 1000\n", "'keyframe.margin_m'"},
      {"radars:\n  - name: left\n    max_range_m: 10000\n",
       "cfg.yaml:3: 'radars[left].max_range_m'"},
      {"radars:\n  - name: left\n    num_samples: 100000000\n",
       "cfg.yaml:3: 'radars[left].num_samples'"},
      {"imaging:\n  mode: coherent\n  coherent_oversampling: 64\nradars:\n  - name: left\n    "
       "num_samples: "
       "100000\n",
       "'imaging.coherent_oversampling'"},
  };
  for (const Case& c : cases) {
    const std::string msg = Refusal(c.yaml);
    EXPECT_NE(msg.find(c.key), std::string::npos) << c.yaml << " -> " << msg;
    EXPECT_NE(msg.find("limits."), std::string::npos) << msg;  // names the budget too
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;       // one line
  }
}

TEST(ConfigLimitsTest, DefaultsAndBundledConfigsFitTheBudgets) {
  EXPECT_EQ(Refusal(""), "");
  EXPECT_NO_THROW(LoadConfig(std::string(UWBSAR_SOURCE_DIR) + "/config/default.yaml"));
  EXPECT_NO_THROW(LoadConfig(std::string(UWBSAR_SOURCE_DIR) + "/config/robot.yaml"));
  // Moderate changes stay accepted: 2 mm pixels with a 5 mm map and 0.25 m tiles; 8 m range.
  EXPECT_EQ(Refusal("imaging:\n  pixel_size_m: 0.002\nslam:\n  map_resolution_m: 0.005\n"
                    "keyframe:\n  tile_length_m: 0.5\n  tile_spacing_m: 0.25\n"),
            "");
  EXPECT_EQ(Refusal("radars:\n  - name: left\n    max_range_m: 8.0\n"), "");
}

TEST(ConfigLimitsTest, BudgetsAreConfigurable) {
  const std::string margin = "keyframe:\n  margin_m: 10\n";
  EXPECT_NE(Refusal(margin), "");
  EXPECT_EQ(Refusal(margin + "limits:\n  max_tile_pixels: 1.0e9\n  max_imaging_memory_mb: 16384\n"),
            "");
  EXPECT_NE(Refusal("limits:\n  max_tile_pixels: 0\n").find("'limits.max_tile_pixels'"),
            std::string::npos);
}

// Issue 45 item 12: a fan of lines every 0.1 degree across 180 degrees took a run from 7 s to
// 158 s. The lines the navigation grid casts per keyframe are budgeted like image sizes:
// (keyframe.tile_length_m / ray_spacing_m + 1) positions x radars x (2 floor(half angle /
// step) + 1) lines; the defaults cast 101 x 2 x 1 = 202.
TEST(ConfigLimitsTest, NavigationRaysPerKeyframeAreBudgetedNamingTheKeys) {
  const std::string nav = "slam:\n  navigation:\n";
  EXPECT_EQ(Refusal(nav + "    ray_half_angle_deg: 90\n    ray_angle_step_deg: 0.1\n"),
            "cfg.yaml:3: 'slam.navigation.ray_half_angle_deg' (90) makes navigation rays per "
            "keyframe (at slam.navigation.ray_angle_step_deg 0.1: 101 positions x 2 radars x 1801 "
            "lines) 3.64e+05, more than limits.max_navigation_rays (2e+04)");
  EXPECT_EQ(
      Refusal(nav + "    ray_spacing_m: 1.0e-5\n"),
      "cfg.yaml:3: 'slam.navigation.ray_spacing_m' (1e-05) makes navigation rays per keyframe "
      "(200001 positions x 2 radars x 1 line) 4e+05, more than limits.max_navigation_rays (2e+04)");
  // A moderate fan fits (45 degrees every degree: 101 x 2 x 91 = 18382), and the budget is a
  // setting.
  EXPECT_EQ(Refusal(nav + "    ray_half_angle_deg: 45\n    ray_angle_step_deg: 1\n"), "");
  EXPECT_EQ(Refusal(nav + "    ray_half_angle_deg: 90\n    ray_angle_step_deg: 0.1\n" +
                    "limits:\n  max_navigation_rays: 4.0e5\n"),
            "");
}

class BoundedFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("uwbsar_bounded_file_test_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(BoundedFileTest, ConfigThatIsNotASmallRegularFileIsRefused) {
  // A device (this used to grow to 23 GB), a folder, and a file over the cap.
  const std::string big = (dir_ / "big.yaml").string();
  {
    std::ofstream out(big);
    const std::string comment = "# " + std::string(1022, 'x') + "\n";
    for (std::uintmax_t n = 0; n <= kMaxYamlFileBytes / comment.size(); ++n) out << comment;
  }
  const std::pair<std::string, std::string> cases[] = {
      {"/dev/zero", "not a regular file"},
      {dir_.string(), "configuration file is a folder"},
      {big, "larger than 4 MiB"},
      {(dir_ / "missing.yaml").string(), "cannot open"}};
  for (const auto& [path, why] : cases) {
    try {
      LoadConfig(path);
      ADD_FAILURE() << path << " was accepted";
    } catch (const ConfigError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;  // names the file first
      EXPECT_NE(msg.find(why), std::string::npos) << msg;
    }
  }
}

TEST_F(BoundedFileTest, MapYamlReaderHasTheSameGuard) {
  EXPECT_THROW(LoadYamlMappingFile("/dev/zero", "map"), InputError);
  const std::string ok = (dir_ / "ok.yaml").string();
  std::ofstream(ok) << "a: 1\n";
  EXPECT_EQ(LoadYamlMappingFile(ok, "map")["a"].as<int>(), 1);
  EXPECT_EQ(ReadBoundedFile(ok, "test"), "a: 1\n");
}

// The map and grid YAML reader is the configuration's: duplicates and a second document are
// refused naming file and line, not resolved by the first one silently.
TEST_F(BoundedFileTest, MapYamlReaderRefusesDuplicateKeysAndSecondDocuments) {
  const std::string dup = (dir_ / "dup.yaml").string();
  std::ofstream(dup) << "image: a.pgm\norigin: [0, 0, 0]\nimage: b.pgm\n";
  try {
    LoadYamlMappingFile(dup, "map");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dup + ":3: duplicate key 'image' (first at line 1)");
  }
  const std::string two = (dir_ / "two.yaml").string();
  std::ofstream(two) << "image: a.pgm\n---\nimage: b.pgm\n";
  try {
    LoadYamlMappingFile(two, "map");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              two + ":2: a second YAML document (after '---'); a file holds one document");
  }
}

}  // namespace
}  // namespace uwbsar
